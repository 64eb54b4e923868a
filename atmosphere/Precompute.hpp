#pragma once
// The precomputation of E. Bruneton, "Precomputed Atmospheric Scattering: a New
// Implementation" (2017), written from its equations for any number of components and
// wavelengths, in double precision on the CPU (OpenMP over texels), with optional
// refraction (eclipse paper, section 4.1: transmittance and scattering follow the rays
// traced by traceRay, Refraction.hpp). All tables are per unit solar irradiance
// (multiply by E_sun(lambda) to get radiance / irradiance).
//
//   transmittance  T(r, mu) to the top of the atmosphere, 2D, the parametrisation of
//                  TextureCoords.hpp (Bruneton's GetTransmittanceTextureUvFromRMu);
//                  Simpson's rule along the (straight or refracted) ray.
//   direct irr.    E_0(r, mu_s) = T(r, mu_s) <cos> (ComputeDirectIrradiance; the average
//                  cosine over the solar disc near the horizon). Not in `irradiance`.
//   single         S_c(r, mu, mu_s, nu) = beta_s,c int_0^d T(x, x_i) T_sun(x_i) rho_c(x_i) dx,
//                  one table per scattering component, without its phase function
//                  (ComputeSingleScattering, trapezoidal rule, the sun's transmittance
//                  with the smoothstep over the solar disc at the horizon).
//   density        J_k(r, mu, mu_s, nu) = sum_c beta_s,c rho_c(r) int_4pi P_c(w.v) L_{k-1}(w) dw,
//                  L_{k-1} the order k-1 radiance plus, for directions towards the ground,
//                  the ground's albedo / pi E_{k-2} attenuated to the point
//                  (ComputeScatteringDensity; sphereSamples x 2 sphereSamples
//                  directions: Gauss-Legendre in mu on either side of the ground's
//                  horizon, midpoint in phi). Computed per (r, mu_s) slice: the incoming
//                  radiance is looked up once per direction and shared by the slice's
//                  (mu, nu) texels; polynomial phases (isotropic, Rayleigh, Penndorf) use the
//                  exact second moments of the incoming radiance, the lobes (closed-form or
//                  tabulated) its cosine modes in azimuth against theirs (AzimuthModes).
//   indirect irr.  E_k(r, mu_s) = int_2pi L_k(w) w_z dw (ComputeIndirectIrradiance).
//   multiple       L_k(r, mu, mu_s, nu) = int_0^d T(x, x_i) J_k(x_i) dx
//                  (ComputeMultipleScattering), summed over orders k >= 2.
// The 4D scattering tables use Bruneton's (r, mu, mu_s, nu) <-> (u_r, u_mu, u_mu_s, u_nu)
// mapping with the ground / non-ground halves of u_mu, stored as 3D tables of
// (NU * MU_S) x MU x R texels; lookups interpolate linearly in all four coordinates
// (nu between slices, mu_s within its own slice, mu within the ray's half).
//
// Refraction: rays from (r, mu) are traced with traceRay (RK4, refractionStepM) and the
// path is interpolated between the steps (cubic Hermite in position); transmittance and
// scattering integrals run along it with the same quadratures as the straight rays (so a
// vertical ray gives the same values). The transmittance table uses each wavelength's
// refractivity (dispersion); the scattering tables use the paths of the reference
// wavelength; the sun's direction is the geometric one at every point and the ground term
// of the density uses straight rays (the simplifications of the eclipse paper, 4.1).
// Transmittance rays bent into the ground continue through it (constant n, the ground's
// extinction), as in the deviation table: the table stays continuous and near 0 there.
#include "Atmosphere.hpp"
#include "TableSizes.hpp"
#include "TextureCoords.hpp"

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace umbra::atmosphere {
namespace stages {
struct ScatterGeometry;
}

/// How the density's sphere of directions is sampled (precompute/ScatteringDensity.cpp):
/// part of the tables' cache keys, so that tables made with another rule are not read back.
inline constexpr const char* kDensityQuadrature =
    "mu Gauss-Legendre split at the ground's horizon, phi midpoint, lobes by their cosine modes in phi, renormalised";

/// How the second order's ground reflection gets the Sun's direct irradiance: part of the
/// keys of the tables it changes (multiple scattering, indirect irradiance).
inline constexpr const char* kGroundSunlight = "E_0 from the transmittance times the visible disc, per point";

/// The sizes default to kDefaultTableSizes (TableSizes.hpp), which also holds the largest
/// that validate() accepts.
struct PrecomputeOptions {
  int transmittanceWidth = kDefaultTableSizes.transmittance[0];   ///< x_mu
  int transmittanceHeight = kDefaultTableSizes.transmittance[1];  ///< x_r
  int scatteringR = kDefaultTableSizes.scattering[0];
  int scatteringMu = kDefaultTableSizes.scattering[1];  ///< even: half for rays that hit the ground
  int scatteringMuS = kDefaultTableSizes.scattering[2];
  int scatteringNu = kDefaultTableSizes.scattering[3];
  int irradianceWidth = kDefaultTableSizes.irradiance[0];   ///< mu_s
  int irradianceHeight = kDefaultTableSizes.irradiance[1];  ///< r
  int orders = kDefaultTableSizes.orders;  ///< scattering orders (1: single only)
  int transmittanceSamples = 500;     ///< Simpson intervals per transmittance ray (even)
  int singleScatteringSamples = 50;   ///< trapezoid intervals per view ray
  int multipleScatteringSamples = 50; ///< trapezoid intervals per view ray
  int opticalDepthSubsamples = 4;     ///< Simpson intervals between two view-ray samples (even)
  /// density: n polar x 2n azimuthal directions, n >= 2 (Bruneton: 16); 0: from the
  /// phase functions (densityDirectionsFor).
  int sphereSamples = 0;
  int irradianceSamples = 32;     ///< indirect irradiance: n/2 polar x 2n azimuthal (Bruneton: 32)
  double muSMin = -0.20791169081775931;  ///< cos(102 deg): the lowest sun in the tables
  double sunAngularRadiusRad = 0.004675;
  bool refraction = false;
  double refractionStepM = 10e3;  ///< RK4 step of the traced rays
  int threads = 0;                ///< OpenMP threads (0: the default)
  /// Wavelengths computed together (0: all). The working tables are this many channels
  /// wide; the final tables hold all wavelengths.
  int wavelengthBatch = 0;
  /// The batches this process computes when several share the work (the ranks of an MPI
  /// run): batch b when b % batchShareCount == batchShareIndex; the other wavelengths'
  /// channels are left 0 (and their orderMeanRadiance). Not in the tables' keys.
  int batchShareIndex = 0, batchShareCount = 1;
  /// The 4D tables a batch makes for a sink (the single scattering, the orders' sum) and
  /// L_k go through an unlinked temporary file (spilledTableDirectory), a few r slices of
  /// each in the process's memory at a time: a batch then holds only J_k whole in memory
  /// (batchBytesPerWavelength). The values are the same. Not in the tables' keys.
  bool spillTables = false;

  /// Empty when usable, else what is wrong.
  std::string validate() const;
  /// The sizes of `sizes` (the Bruneton tables' and the orders; the rest as it is).
  PrecomputeOptions& withSizes(const TableSizes& sizes);
};

/// The memory one wavelength of a batch holds at the precomputation's peak [bytes], for
/// `scatterers` scattering components, with the tables handed on as they are finished
/// (BatchTablesSink), in float: the 4D tables alive at once (the single scattering and J_2
/// in the second order, or J_k, L_k and the multiple scattering after it); with
/// options.spillTables J_k and the few r slices of the others that the stages work on
/// (kSpilledSlices of each).
std::size_t batchBytesPerWavelength(const PrecomputeOptions& options, int scatterers);
/// The r slices of each spilled 4D table that batchBytesPerWavelength counts in memory.
constexpr int kSpilledSlices = 4;
/// The wavelengths of a batch whose memory (batchBytesPerWavelength) fits budgetBytes:
/// `wavelengths` when all fit, else the fewest batches that fit, as even as they can be
/// (at least 1 wavelength).
int wavelengthBatchFor(const PrecomputeOptions& options, int scatterers, int wavelengths, std::size_t budgetBytes);

/// The density directions an atmosphere's phase functions need (sphereSamples 0): the
/// polar spacing pi / n no wider than 1.5 times the half width of the narrowest forward peak
/// (the angle at which a phase function falls to half its forward value) of the components
/// that hold at least kMinDensityShare of the scattering optical depth, n a multiple of
/// 8 in [16, 64]. Rayleigh and Earth's haze: 16; Mars' dust, whose Lorenz-Mie diffraction
/// peak is a few degrees wide: more (docs/accuracy-vs-speed/atmosphere-tables.md, "Density directions").
int densityDirectionsFor(const Atmosphere& atmosphere);
/// The share of a wavelength's scattering optical depth below which a component's forward
/// peak does not set densityDirectionsFor.
constexpr double kMinDensityShare = 0.1;
/// The fewest densityDirectionsFor gives (Bruneton's count): more means a forward peak.
inline constexpr int kMinDensityDirections = 16;

/// A 2D table, `channels` values (one per wavelength) per texel, row by row.
struct Table2D {
  int width = 0, height = 0, channels = 0;
  std::vector<double> values;

  void resize(int w, int h, int c) {
    width = w, height = h, channels = c;
    values.assign(static_cast<std::size_t>(w) * h * c, 0.0);
  }
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * width + x) * channels;
  }
  const double* at(int x, int y) const { return values.data() + offset(x, y); }
  double* at(int x, int y) { return values.data() + offset(x, y); }
};

/// Memory for the 4D tables: from 2 MiB on, whole pages of its own (mapped, in transparent
/// huge pages where the kernel gives them: one page fault per 2 MiB rather than per 4 KiB,
/// and in a virtual machine the faults of a table's first writing cost as much as computing
/// it), given back whole when freed; smaller, the heap's. freeTableMemory takes the same
/// bytes. zeroTableMemory zeroes on every thread, so that the faults are shared too.
void* allocateTableMemory(std::size_t bytes);
void freeTableMemory(void* data, std::size_t bytes) noexcept;
void zeroTableMemory(void* data, std::size_t bytes);
/// Whether a table of `bytes` asked to spill does: from 2 MiB on (smaller ones are the heap's).
bool spillsTableMemory(std::size_t bytes);
/// While one lives, allocateTableMemory on this thread maps the tables that spill
/// (spillsTableMemory) from an unlinked temporary file in spilledTableDirectory(), made to
/// their size (zero), shared: the pages the process lets go (releaseTableMemory) keep their
/// values in the kernel's page cache, which writes them to the disk when memory is short,
/// and come back from it when next touched. Throws std::runtime_error naming the directory
/// when it cannot make the file.
struct SpilledTableMemory {
  SpilledTableMemory();
  ~SpilledTableMemory();
  SpilledTableMemory(const SpilledTableMemory&) = delete;
  SpilledTableMemory& operator=(const SpilledTableMemory&) = delete;
};
/// $TMPDIR, else /tmp.
std::string spilledTableDirectory();
/// Lets the whole pages within [data, data + bytes) of a spilled table go from the process's
/// memory (their values stay in the file).
void releaseTableMemory(const void* data, std::size_t bytes) noexcept;
/// Copies `bytes` between memory and a spilled table (`table`: its first value) from byte
/// `offset` on, through its file (pread, pwrite: no page of the table mapped into the
/// process). Throws std::runtime_error when the file cannot be read or written.
void copySpilledTableMemory(const void* table, std::size_t offset, void* memory, std::size_t bytes, bool toTable);
/// Brings the pages of [data, data + bytes) of a spilled table into the process's memory in
/// one call, rather than a page fault each; nothing where the kernel cannot.
void populateTableMemory(const void* data, std::size_t bytes) noexcept;

/// Whether a table's values are spilled (SpilledTableMemory): moved with them, never copied
/// (a copy is the heap's).
struct SpillMark {
  bool on = false;
  SpillMark() = default;
  SpillMark(const SpillMark&) noexcept {}
  SpillMark& operator=(const SpillMark&) noexcept {
    on = false;
    return *this;
  }
  SpillMark(SpillMark&& o) noexcept : on(o.on) { o.on = false; }
  SpillMark& operator=(SpillMark&& o) noexcept {
    on = o.on, o.on = false;
    return *this;
  }
};

/// A std::vector allocator of table memory whose resize() leaves the values unset (the
/// table's resize zeroes them, in parallel).
template <class T>
struct TableAllocator {
  using value_type = T;
  TableAllocator() = default;
  template <class U>
  TableAllocator(const TableAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocateTableMemory(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { freeTableMemory(p, n * sizeof(T)); }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialised: a float is left unset
  }
  template <class U>
  bool operator==(const TableAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const TableAllocator<U>&) const noexcept { return false; }
};

/// A 3D table (width = NU * MU_S, height = MU, depth = R for the scattering tables).
template <class Value>
struct BasicTable3D {
  int width = 0, height = 0, depth = 0, channels = 0;
  std::vector<Value, TableAllocator<Value>> values;
  SpillMark spilled;

  /// The size, every value zero; spill: in a temporary file (SpilledTableMemory) when the
  /// table is large enough (spillsTableMemory).
  void resize(int w, int h, int d, int c, bool spill = false) {
    width = w, height = h, depth = d, channels = c;
    std::vector<Value, TableAllocator<Value>>().swap(values);
    const std::size_t n = static_cast<std::size_t>(w) * h * d * c;
    spilled.on = spill && spillsTableMemory(n * sizeof(Value));
    if (spilled.on) {
      const SpilledTableMemory scope;
      values.resize(n);  // the file's zeros
    } else {
      values.resize(n);
      zeroTableMemory(values.data(), values.size() * sizeof(Value));
    }
  }
  /// A spilled table's r slices [z0, z1) leave the process's memory (releaseTableMemory);
  /// nothing for another.
  void release(int z0, int z1) const {
    if (!spilled.on || values.empty() || z1 <= z0) return;
    releaseTableMemory(at(0, 0, z0), (offset(0, 0, z1) - offset(0, 0, z0)) * sizeof(Value));
  }
  void releaseAll() const { release(0, depth); }
  /// A spilled table's r slices [z0, z1) brought into memory ahead of reading them
  /// (populateTableMemory); nothing for another.
  void populate(int z0, int z1) const {
    z0 = std::max(z0, 0), z1 = std::min(z1, depth);
    if (!spilled.on || values.empty() || z1 <= z0) return;
    populateTableMemory(at(0, 0, z0), (offset(0, 0, z1) - offset(0, 0, z0)) * sizeof(Value));
  }
  std::size_t offset(int x, int y, int z) const {
    return ((static_cast<std::size_t>(z) * height + y) * width + x) * channels;
  }
  const Value* at(int x, int y, int z) const { return values.data() + offset(x, y, z); }
  Value* at(int x, int y, int z) { return values.data() + offset(x, y, z); }
};
/// The 4D tables, finished (AtmosphereTables) and the orders' working ones (J_k, L_k), in
/// single precision as the EXR files and the GPU hold them (a relative 6e-8, far below the
/// tables' interpolation error): half the memory of double, the precomputation's largest
/// share of it.
using FloatTable3D = BasicTable3D<float>;

struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

struct AtmosphereTables {
  PrecomputeOptions options;
  double bottomRadiusM = 0.0;
  double topRadiusM = 0.0;
  std::vector<double> wavelengthsNm;

  Table2D transmittance;  ///< T to the top, (x_mu, x_r)
  /// Names of the components that scatter, in the atmosphere's order; one single-scattering
  /// table each (without the phase function).
  std::vector<std::string> scatteringComponents;
  std::vector<FloatTable3D> singleScattering;
  FloatTable3D multipleScattering;  ///< orders 2..N, phase functions included
  Table2D directIrradiance;    ///< E_0 (mu_s, r)
  Table2D irradiance;          ///< indirect, orders 1..N-1 (mu_s, r), as Bruneton's

  /// Per order k = 1..N (index k - 1), per wavelength: the mean over the scattering
  /// texels of the order's radiance L_k (phases included).
  std::vector<std::vector<double>> orderMeanRadiance;
  std::vector<StageTiming> timings;  ///< seconds per stage (summed over orders/batches)

  ShellRadii shell() const { return {bottomRadiusM, topRadiusM}; }
  std::size_t wavelengthCount() const { return wavelengthsNm.size(); }
  std::size_t bytes() const;  ///< memory held by the tables
};

/// Thrown when the progress callback returns false.
class PrecomputeCancelled : public std::runtime_error {
public:
  PrecomputeCancelled() : std::runtime_error("precomputation cancelled") {}
};

/// `progress(fraction, stage)` is called from the calling thread between chunks of work;
/// returning false cancels (PrecomputeCancelled). Throws std::invalid_argument for invalid
/// options or an invalid atmosphere.
using PrecomputeProgress = std::function<bool(double fraction, const std::string& stage)>;
AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& options = {},
                            const PrecomputeProgress& progress = {});

/// Where precompute() hands the finished 4D tables of each batch of wavelengths when it is
/// given one, each as soon as it is finished: the batch's first channel, which table
/// (0 .. scattering components - 1: that component's single scattering; the number of
/// scattering components: the multiple scattering), and its values, as many channels wide
/// as the batch (a batch's channels are consecutive), to read before it returns (a batch of
/// every wavelength hands on whole tables, written as they are; spilled ones, options.
/// spillTables, are read back from their file as the sink goes, and let go after it). The
/// tables precompute() returns then hold no 4D values (singleScattering and
/// multipleScattering empty), so that no 4D table is ever held for every wavelength: the
/// peak memory is one batch's working tables.
using BatchTablesSink = std::function<void(int firstChannel, int table, const FloatTable3D& values)>;
AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& options,
                            const PrecomputeProgress& progress, const BatchTablesSink& sink);

// ---- the 4D parametrisation (Bruneton 2017, GetScatteringTextureUvwzFromRMuMuSNu) -------

struct ScatteringTableSize {
  int r = kDefaultTableSizes.scattering[0], mu = kDefaultTableSizes.scattering[1];
  int muS = kDefaultTableSizes.scattering[2], nu = kDefaultTableSizes.scattering[3];
};
struct ScatteringCoords {
  double uNu = 0.0, uMuS = 0.0, uMu = 0.0, uR = 0.0;  ///< texture coordinates in [0, 1]
};
struct ScatteringPoint {
  double r = 0.0, mu = 0.0, muS = 0.0, nu = 0.0;
  bool rayIntersectsGround = false;
};
ScatteringCoords scatteringCoordsFromRMuMuSNu(const ShellRadii& shell, const ScatteringTableSize& size,
                                              double muSMin, double r, double mu, double muS, double nu,
                                              bool rayIntersectsGround);
ScatteringPoint rMuMuSNuFromScatteringCoords(const ShellRadii& shell, const ScatteringTableSize& size,
                                             double muSMin, const ScatteringCoords& coords);
/// The configuration at the centre of texel (x, y, z) (x = nu index * MU_S + mu_s index), nu
/// clamped to the range the other three allow.
ScatteringPoint scatteringTexelPoint(const ShellRadii& shell, const ScatteringTableSize& size,
                                     double muSMin, int x, int y, int z);

// ---- lookups (all per unit solar irradiance, one value per wavelength) -------------------

/// T from (r, mu) to the top (mu at or above the horizon; below it the horizon's value).
std::vector<double> transmittanceToTop(const AtmosphereTables& tables, double r, double mu);
/// The same into out[0..channels).
void transmittanceToTop(const AtmosphereTables& tables, double r, double mu, double* out);
/// T between (r, mu) and the point at distance d along the straight ray (Bruneton 2017,
/// GetTransmittance): a ratio of two transmittances to the top, taken upwards for a ray
/// that hits the ground. endsOnGround: the point is on the ground (its radius the bottom's).
std::vector<double> transmittanceAlong(const AtmosphereTables& tables, double r, double mu, double d,
                                       bool rayIntersectsGround, bool endsOnGround = false);
/// Quadrilinear lookup in a scattering table.
std::vector<double> lookupScattering(const AtmosphereTables& tables, const FloatTable3D& table, double r,
                                     double mu, double muS, double nu, bool rayIntersectsGround);
/// Single (each component's table times its phase at nu) plus multiple scattering, times
/// solarIrradiance (per wavelength; empty: 1). Straight-ray ground test for the half.
/// The tables hold the Sun down to options.muSMin, below which the air is taken to be in
/// the planet's shadow (cos 102 deg: the shadow's edge at the top of the atmosphere is at
/// 100.1 deg for Earth, 102.3 deg for Mars, whose air above 76 km is left dark between
/// the two). For a lower Sun the light comes from where the ray first reaches sunlit air,
/// at d = distanceToSunCosineM: T(x, x_d) S(x_d), and nothing when the ray ends first (the
/// night sky is black, a limb ray that runs into the day side is not).
std::vector<double> skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r,
                                double mu, double muS, double nu,
                                const std::vector<double>& solarIrradiance = {});
/// The same per unit solar irradiance into L (wavelengthCount() values), without allocating
/// for up to 64 wavelengths.
void skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu, double muS,
                 double nu, double* L);
/// skyRadiance (per unit solar irradiance) for many lookups in the same tables: their
/// geometry and the components' phase functions found once. Keeps references to both.
class SkyRadianceLookup {
public:
  SkyRadianceLookup(const AtmosphereTables& tables, const Atmosphere& atmosphere);
  void operator()(double r, double mu, double muS, double nu, double* L) const;

private:
  const AtmosphereTables& tables_;
  std::shared_ptr<const stages::ScatterGeometry> geometry_;
  std::vector<const PhaseFunction*> phases_;  ///< [component * wavelengths + wavelength]
  std::vector<bool> sharedSamples_;  ///< per component: tabulated on the same samples at every wavelength
};
/// The cosine factor of the direct irradiance on a horizontal surface from a Sun of angular
/// radius alphaRad whose centre is at zenith cosine muS: muS above alphaRad, 0 below
/// -alphaRad, (muS + alphaRad)^2 / (4 alphaRad) between, the disc partly set (Bruneton 2017).
double sunDiscCosine(double muS, double alphaRad);
/// Bilinear lookup in the indirect irradiance table; zero for a Sun below the tables'
/// lowest (muS < options.muSMin), where the sky is dark (skyRadiance) and the table's cells
/// hold only what the precomputation leaks from that lowest Sun (at night comparable to the
/// Moon's light on the ground, far brighter than it in a lunar eclipse).
std::vector<double> indirectIrradiance(const AtmosphereTables& tables, double r, double muS);
/// The direct irradiance E_0 on a horizontal surface: the transmittance to the top along
/// muS times sunDiscCosine (options.sunAngularRadiusRad), as its table's texels hold, but
/// computed where asked and not interpolated across the table's mu_s cells: those are
/// 1.8 deg wide at 64 cells, and across the Sun's setting the interpolation was x19 too
/// bright with the Sun on the horizon (docs/accuracy-vs-speed/atmosphere-tables.md, "Twilight in the render
/// pass"). The precomputation's second order takes its ground's E_0 the same way; the
/// table is still written, for the table files.
std::vector<double> directIrradiance(const AtmosphereTables& tables, double r, double muS);

}  // namespace umbra::atmosphere
