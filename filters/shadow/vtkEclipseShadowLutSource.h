#pragma once
// vtkEclipseShadowLutSource: the eclipse-shadow lookup table (eclipse paper, Eq. 3-4) as a
// 2D vtkImageData of I / I_sun (float RGB point scalars "I_over_Isun"), point coordinates
// (u, v) at texel centres, the defining parameters in field data. Built by
// umbra::eclipse::buildAirlessShadowLut, cached on disk as EXR keyed by a parameter hash.
//
// The bodies (Sun and occluder) are carried into the output's field data for the filters
// downstream; they do not change the airless table's values and are not part of its key.
//
// With an atmosphere (SetAtmosphere, vtkEclipseAtmosphereSource) the table is the
// atmospheric shadow LuT of umbra::eclipse::buildAtmosphericShadowLut (refracted Sun and
// in-scattered light summed over limb views, plus the direct light past r_atmo), cached
// under kind "eclipse-shadow-atmosphere" keyed by every parameter of the atmosphere, its
// tables and the limb views. Only the requested update extent is computed (e.g. the u
// range where a scene's receiver can be); a partial extent is cached separately. Without
// one, the airless LuT, bit for bit as before.
#include "vtkEclipseAtmosphereSource.h"

#include <string>

class vtkImageData;

class vtkEclipseShadowLutSource : public vtkEclipseAtmosphereSource {
public:
  static vtkEclipseShadowLutSource* New();
  vtkTypeMacro(vtkEclipseShadowLutSource, vtkEclipseAtmosphereSource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Texels along u and v (default 256 x 256).
  vtkSetClampMacro(Width, int, 2, 16384);
  vtkGetMacro(Width, int);
  vtkSetClampMacro(Height, int, 2, 16384);
  vtkGetMacro(Height, int);
  /// Linear limb-darkening coefficient u of Eq. 1 (default 0.6).
  vtkSetClampMacro(LimbDarkening, double, 0.0, 1.0);
  vtkGetMacro(LimbDarkening, double);
  /// Relative tolerance of the per-texel quadrature (default 1e-10).
  vtkSetClampMacro(RelativeTolerance, double, 1e-15, 1e-2);
  vtkGetMacro(RelativeTolerance, double);

  /// Limb views (atmosphere only): rows = columns = LimbSize (default 256), the in-scattered
  /// light on ScatteringCells x ScatteringCells cells (default 16).
  vtkSetClampMacro(LimbSize, int, 1, 65536);
  vtkGetMacro(LimbSize, int);
  vtkSetClampMacro(ScatteringCells, int, 1, 65536);
  vtkGetMacro(ScatteringCells, int);

protected:
  vtkEclipseShadowLutSource();
  ~vtkEclipseShadowLutSource() override = default;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkEclipseShadowLutSource(const vtkEclipseShadowLutSource&) = delete;
  void operator=(const vtkEclipseShadowLutSource&) = delete;

  int Width = 256;
  int Height = 256;
  double LimbDarkening = 0.6;
  double RelativeTolerance = 1e-10;
  int LimbSize = 256;
  int ScatteringCells = 16;

  int RequestAtmospheric(vtkInformation* outInfo, vtkImageData* output);
};
