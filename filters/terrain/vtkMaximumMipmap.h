#pragma once
// vtkMaximumMipmap: one level of the maximum mipmap of a DEM (terrain paper, section 3.2;
// umbra::terrain::MaximumMipmap). Input: a 2D vtkImageData of heights (see
// TerrainImageData.h). Output: a 2D image with one sample per texel of the level, placed at
// the texel's centre, point scalars "max_height_m" (-inf where the texel holds no data);
// field data "levels" gives the number of levels.
#include <vtkImageAlgorithm.h>

#include <string>

class vtkMaximumMipmap : public vtkImageAlgorithm {
public:
  static vtkMaximumMipmap* New();
  vtkTypeMacro(vtkMaximumMipmap, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// 0: per grid cell (the four corners); m: blocks of 2^m x 2^m cells. Clamped to the top.
  vtkSetClampMacro(Level, int, 0, 30);
  vtkGetMacro(Level, int);
  vtkSetStdStringFromCharMacro(HeightArrayName);
  vtkGetCharFromStdStringMacro(HeightArrayName);

protected:
  vtkMaximumMipmap() = default;
  ~vtkMaximumMipmap() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMaximumMipmap(const vtkMaximumMipmap&) = delete;
  void operator=(const vtkMaximumMipmap&) = delete;

  int Level = 0;
  std::string HeightArrayName;
};
