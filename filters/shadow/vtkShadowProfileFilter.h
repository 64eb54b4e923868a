#pragma once
// vtkShadowProfileFilter: a cross-section of an occluder's shadow at a receiver distance.
// Input: a shadow LuT (vtkEclipseShadowLutSource's output; optional with Exact on). Output: a vtkTable with the
// columns offset_km, r, g, b, luminance (I / I_sun) from the shadow axis outwards.
// With Exact on, each sample is computed directly instead of looked up in the LuT.
#include <vtkTableAlgorithm.h>

class vtkShadowProfileFilter : public vtkTableAlgorithm {
public:
  static vtkShadowProfileFilter* New();
  vtkTypeMacro(vtkShadowProfileFilter, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The bodies [m]. Zero (default) = take them from the LuT's field data.
  vtkSetMacro(SunRadiusM, double);
  vtkGetMacro(SunRadiusM, double);
  vtkSetMacro(OccluderRadiusM, double);
  vtkGetMacro(OccluderRadiusM, double);
  vtkSetMacro(SunOccluderDistanceM, double);
  vtkGetMacro(SunOccluderDistanceM, double);
  /// Distance of the cross-section behind the occluder's centre, along the shadow axis [m].
  vtkSetMacro(ReceiverDistanceM, double);
  vtkGetMacro(ReceiverDistanceM, double);
  /// Largest offset from the axis [m]; 0 (default) = 1.25 x the penumbra's radius.
  vtkSetMacro(MaxOffsetM, double);
  vtkGetMacro(MaxOffsetM, double);
  vtkSetClampMacro(Samples, int, 2, 10000000);
  vtkGetMacro(Samples, int);
  /// Compute every sample directly (limb-darkened quadrature) instead of from the LuT.
  vtkSetMacro(Exact, bool);
  vtkGetMacro(Exact, bool);
  vtkBooleanMacro(Exact, bool);
  vtkSetClampMacro(LimbDarkening, double, 0.0, 1.0);
  vtkGetMacro(LimbDarkening, double);

protected:
  vtkShadowProfileFilter() = default;
  ~vtkShadowProfileFilter() override = default;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkShadowProfileFilter(const vtkShadowProfileFilter&) = delete;
  void operator=(const vtkShadowProfileFilter&) = delete;

  double SunRadiusM = 0.0;
  double OccluderRadiusM = 0.0;
  double SunOccluderDistanceM = 0.0;
  double ReceiverDistanceM = 384400e3;
  double MaxOffsetM = 0.0;
  int Samples = 1001;
  bool Exact = false;
  double LimbDarkening = 0.6;
};
