#pragma once
// vtkTerrainHorizonShadowFilter: the visible fraction of the solar disc at every sample of
// a DEM (terrain paper, section 3). Input: a 2D vtkImageData of heights [m] above the
// body's sphere (see TerrainImageData.h). Output: the input with a point-data array
// "visible_solar_fraction" (0 = umbra, 1 = fully lit). The Sun is a direction in the DEM's
// tangent frame (x = +i, y = +j, z = up at the DEM's centre); umbra::terrain::
// bodyFixedToTangent turns a body-fixed one (from an ephemeris) into it.
#include <vtkImageAlgorithm.h>

#include <string>

class vtkTerrainHorizonShadowFilter : public vtkImageAlgorithm {
public:
  static vtkTerrainHorizonShadowFilter* New();
  vtkTypeMacro(vtkTerrainHorizonShadowFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// terrain::ShadowMethod's, in its order.
  enum Method { DP = 0, UNIFORM = 1, REFERENCE = 2, CELLS = 3 };

  /// Towards the Sun's centre, tangent frame (need not be normalised). Default: zenith.
  vtkSetVector3Macro(SunDirection, double);
  vtkGetVector3Macro(SunDirection, double);
  /// Convenience: the direction from an elevation and an azimuth (from +y towards +x).
  void SetSunElevationAzimuthDeg(double elevationDeg, double azimuthDeg);
  /// Angular radius of the Sun [rad] (default: at 1 au).
  vtkSetClampMacro(SunAngularRadiusRad, double, 1e-7, 0.5);
  vtkGetMacro(SunAngularRadiusRad, double);
  /// Linear limb darkening (0: uniform disc, Eq. 7).
  vtkSetClampMacro(LimbDarkening, double, 0.0, 1.0);
  vtkGetMacro(LimbDarkening, double);
  vtkSetMacro(BodyRadiusM, double);
  vtkGetMacro(BodyRadiusM, double);

  vtkSetClampMacro(Method, int, DP, CELLS);
  vtkGetMacro(Method, int);
  /// N': mip levels per concatenated interval (DP).
  vtkSetClampMacro(Levels, int, 1, 30);
  vtkGetMacro(Levels, int);
  vtkSetClampMacro(UniformSteps, int, 1, 1 << 20);
  vtkGetMacro(UniformSteps, int);
  vtkSetClampMacro(ReferenceStrips, int, 2, 4096);
  vtkGetMacro(ReferenceStrips, int);
  vtkSetClampMacro(ReferenceStepTexels, double, 1e-3, 16.0);
  vtkGetMacro(ReferenceStepTexels, double);

  /// Heights array of the input (empty: active scalars) and an optional no-data value.
  vtkSetStdStringFromCharMacro(HeightArrayName);
  vtkGetCharFromStdStringMacro(HeightArrayName);
  void SetNoDataValue(double value);
  void ClearNoDataValue();

  /// Heights / texels looked at by the last update (a measure of the work).
  vtkGetMacro(SamplesLookedAt, long long);

protected:
  vtkTerrainHorizonShadowFilter() = default;
  ~vtkTerrainHorizonShadowFilter() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkTerrainHorizonShadowFilter(const vtkTerrainHorizonShadowFilter&) = delete;
  void operator=(const vtkTerrainHorizonShadowFilter&) = delete;

  double SunDirection[3] = {0.0, 0.0, 1.0};
  double SunAngularRadiusRad = 696342e3 / 149597870700.0;
  double LimbDarkening = 0.0;
  double BodyRadiusM = 1737.4e3;
  int Method = DP;
  int Levels = 6;
  int UniformSteps = 128;
  int ReferenceStrips = 32;
  double ReferenceStepTexels = 0.125;
  std::string HeightArrayName;
  bool HasNoDataValue = false;
  double NoDataValue = 0.0;
  long long SamplesLookedAt = 0;
};
