#pragma once
// vtkLimbLuminanceSource: the limb-luminance LuT of an occluder with an atmosphere (eclipse
// paper, 5.3): for each (u, v) of the shadow LuT's parametrisation the limb view from that
// point, 64 columns around half the ring, averaged down to `Layers` rows. Output: a 3D
// vtkImageData Width x Height x (Columns * Layers) of float RGB point scalars
// "L_over_Esun" (radiance per unit solar irradiance [1/sr], R, G, B = 680, 550, 440 nm),
// value (i, j, layer * Columns + column), point coordinates (u, v) at texel centres in x, y
// and the slice index in z. Built by umbra::eclipse::buildLimbLuminanceLut; cached as EXR
// (kind "eclipse-limb-luminance", the slices stacked: height Height * depth) keyed by every
// parameter. Needs an atmosphere (SetAtmosphere). With u and v ranges (SetLutRange, as the
// shadow LuT's) the texel centres are in them; they go to the field data and the cache key
// (filters::addLutRange: uMin, uMax, vMin, vMax, vLowFraction).
#include "vtkEclipseAtmosphereSource.h"

class vtkLimbLuminanceSource : public vtkEclipseAtmosphereSource {
public:
  static vtkLimbLuminanceSource* New();
  vtkTypeMacro(vtkLimbLuminanceSource, vtkEclipseAtmosphereSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Texels along u and v (default 64 x 64), columns per view (64), rows kept (1).
  vtkSetClampMacro(Width, int, 2, 4096);
  vtkGetMacro(Width, int);
  vtkSetClampMacro(Height, int, 2, 4096);
  vtkGetMacro(Height, int);
  vtkSetClampMacro(Columns, int, 1, 4096);
  vtkGetMacro(Columns, int);
  vtkSetClampMacro(Layers, int, 1, 256);
  vtkGetMacro(Layers, int);
  /// Rows of each limb view before the layers are averaged (default 256); in-scattered
  /// light on ScatteringCells x ScatteringCells cells (default 32).
  vtkSetClampMacro(LimbRows, int, 1, 65536);
  vtkGetMacro(LimbRows, int);
  vtkSetClampMacro(ScatteringCells, int, 1, 65536);
  vtkGetMacro(ScatteringCells, int);
  vtkSetClampMacro(LimbDarkening, double, 0.0, 1.0);
  vtkGetMacro(LimbDarkening, double);

protected:
  vtkLimbLuminanceSource() = default;
  ~vtkLimbLuminanceSource() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkLimbLuminanceSource(const vtkLimbLuminanceSource&) = delete;
  void operator=(const vtkLimbLuminanceSource&) = delete;

  int Width = 64, Height = 64, Columns = 64, Layers = 1, LimbRows = 256, ScatteringCells = 32;
  double LimbDarkening = 0.6;
};
