#include "Precompute.hpp"
#include "Quadrature.hpp"

#include "Refraction.hpp"
#include "SightLines.hpp"  // refractiveMedium
#include "TextureCoords.hpp"
#include "precompute/Batch.hpp"
#include "precompute/Kernels.hpp"
#include "precompute/Model.hpp"
#include "precompute/Parametrisation.hpp"
#include "precompute/Paths.hpp"
#include "precompute/Runner.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <new>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <cerrno>
#include <cstdint>
#include <fcntl.h>
#include <stdexcept>
#include <sys/mman.h>
#include <unistd.h>

namespace umbra::atmosphere {

using namespace stages;

// ---- options -------------------------------------------------------------------------------

PrecomputeOptions& PrecomputeOptions::withSizes(const TableSizes& s) {
  transmittanceWidth = s.transmittance[0], transmittanceHeight = s.transmittance[1];
  scatteringR = s.scattering[0], scatteringMu = s.scattering[1], scatteringMuS = s.scattering[2];
  scatteringNu = s.scattering[3];
  irradianceWidth = s.irradiance[0], irradianceHeight = s.irradiance[1];
  orders = s.orders;
  return *this;
}

std::string PrecomputeOptions::validate() const {
  std::ostringstream e;
  const auto side = [](int n) { return n >= 2 && n <= kMaxTableSide; };
  const auto cells = [](int n) { return n >= 2 && n <= kMaxScatteringCells; };
  if (!side(transmittanceWidth) || !side(transmittanceHeight))
    e << "transmittance size must be 2 to " << kMaxTableSide << " texels a side; ";
  if (!cells(scatteringR) || !cells(scatteringMuS) || !cells(scatteringNu))
    e << "scattering R, MU_S, NU must be 2 to " << kMaxScatteringCells << "; ";
  if (!cells(scatteringMu) || scatteringMu < 4 || scatteringMu % 2 != 0)
    e << "scatteringMu must be even and 4 to " << kMaxScatteringCells << "; ";
  if (!side(irradianceWidth) || !side(irradianceHeight))
    e << "irradiance size must be 2 to " << kMaxTableSide << " texels a side; ";
  if (orders < 1 || orders > kMaxOrders) e << "orders must be 1 to " << kMaxOrders << "; ";
  if (transmittanceSamples < 2 || transmittanceSamples % 2 != 0) e << "transmittanceSamples must be even and >= 2; ";
  if (singleScatteringSamples < 1 || multipleScatteringSamples < 1) e << "scattering samples must be >= 1; ";
  if (opticalDepthSubsamples < 2 || opticalDepthSubsamples % 2 != 0) e << "opticalDepthSubsamples must be even and >= 2; ";
  if (sphereSamples != 0 && sphereSamples < 2) e << "sphereSamples must be 0 (from the phase functions) or >= 2; ";
  if (irradianceSamples < 2 || irradianceSamples % 2 != 0) e << "irradianceSamples must be even and >= 2; ";
  if (!(muSMin >= -1.0 && muSMin < 1.0)) e << "muSMin must be in [-1, 1); ";
  if (!(sunAngularRadiusRad >= 0.0 && sunAngularRadiusRad < 0.5)) e << "sunAngularRadiusRad must be in [0, 0.5); ";
  if (!(refractionStepM > 0.0)) e << "refractionStepM must be > 0; ";
  if (wavelengthBatch < 0) e << "wavelengthBatch must be >= 0; ";
  if (batchShareCount < 1 || batchShareIndex < 0 || batchShareIndex >= batchShareCount)
    e << "batchShareIndex must be in [0, batchShareCount); ";
  return e.str();
}

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
std::size_t mappedBytes(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }
thread_local int spillScopes = 0;  // SpilledTableMemory's alive on this thread

/// The open file of each spilled table, by its first byte (copySpilledTableMemory).
std::mutex spilledFilesMutex;
std::map<const void*, int>& spilledFiles() {
  static std::map<const void*, int> files;
  return files;
}

/// A shared mapping of `size` bytes of a new unlinked file in spilledTableDirectory().
void* mapSpilledFile(std::size_t size) {
  const std::string dir = spilledTableDirectory();
  const auto fail = [&](const char* what) {
    throw std::runtime_error("spilled tables: cannot " + std::string(what) + " a temporary file of " +
                             std::to_string(size >> 20) + " MiB in " + dir + ": " + std::strerror(errno));
  };
  int fd = -1;
#ifdef O_TMPFILE
  fd = ::open(dir.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
#endif
  if (fd < 0) {  // a file system without O_TMPFILE: a named one, unlinked at once
    std::string name = dir + "/umbra-tables-XXXXXX";
    fd = ::mkstemp(name.data());
    if (fd < 0) fail("make");
    ::unlink(name.c_str());
  }
  // The blocks reserved now: a full disk is this error, not a SIGBUS at a page's first write.
  if (::fallocate(fd, 0, 0, static_cast<off_t>(size)) != 0 &&
      (errno != EOPNOTSUPP || ::ftruncate(fd, static_cast<off_t>(size)) != 0)) {
    ::close(fd);
    fail("reserve");
  }
  void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  if (p == MAP_FAILED) {
    ::close(fd);
    fail("map");
  }
  const std::lock_guard<std::mutex> lock(spilledFilesMutex);
  spilledFiles()[p] = fd;
  return p;
}
}  // namespace

std::string spilledTableDirectory() {
  const char* d = std::getenv("TMPDIR");
  return d && *d ? d : "/tmp";
}

bool spillsTableMemory(std::size_t bytes) { return bytes >= kHugePage; }

SpilledTableMemory::SpilledTableMemory() { ++spillScopes; }
SpilledTableMemory::~SpilledTableMemory() { --spillScopes; }

void releaseTableMemory(const void* data, std::size_t bytes) noexcept {
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(data), end = begin + bytes;
  const std::uintptr_t from = (begin + page - 1) / page * page, to = end / page * page;
  if (to > from) (void)::madvise(reinterpret_cast<void*>(from), to - from, MADV_DONTNEED);
}

void populateTableMemory(const void* data, std::size_t bytes) noexcept {
  constexpr int kPopulateRead = 22;  // MADV_POPULATE_READ, Linux 5.14 (an error before: then faults)
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(data) / page * page;
  const auto end = reinterpret_cast<std::uintptr_t>(data) + bytes;
  if (end > begin) (void)::madvise(reinterpret_cast<void*>(begin), end - begin, kPopulateRead);
}

void* allocateTableMemory(std::size_t bytes) {
  if (spillScopes > 0 && spillsTableMemory(bytes)) return mapSpilledFile(mappedBytes(bytes));
  if (bytes < kHugePage) {
    void* p = std::malloc(std::max<std::size_t>(bytes, 1));
    if (!p) throw std::bad_alloc();
    return p;
  }
  const std::size_t size = mappedBytes(bytes);
  void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)::madvise(p, size, MADV_HUGEPAGE);  // a hint: without it, 4 KiB pages
#endif
  return p;
}

void freeTableMemory(void* data, std::size_t bytes) noexcept {
  if (!data) return;
  if (bytes < kHugePage) return std::free(data);
  ::munmap(data, mappedBytes(bytes));
  const std::lock_guard<std::mutex> lock(spilledFilesMutex);
  if (auto it = spilledFiles().find(data); it != spilledFiles().end()) {
    ::close(it->second);
    spilledFiles().erase(it);
  }
}

void copySpilledTableMemory(const void* table, std::size_t offset, void* memory, std::size_t bytes, bool toTable) {
  int fd = -1;
  {
    const std::lock_guard<std::mutex> lock(spilledFilesMutex);
    if (auto it = spilledFiles().find(table); it != spilledFiles().end()) fd = it->second;
  }
  if (fd < 0) throw std::logic_error("copySpilledTableMemory: not a spilled table");
  auto* p = static_cast<char*>(memory);
  for (std::size_t done = 0; done < bytes;) {
    const off_t at = static_cast<off_t>(offset + done);
    const ssize_t n = toTable ? ::pwrite(fd, p + done, bytes - done, at) : ::pread(fd, p + done, bytes - done, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw std::runtime_error("spilled tables: cannot " + std::string(toTable ? "write" : "read") + " their file in " +
                               spilledTableDirectory() + ": " + (n < 0 ? std::strerror(errno) : "end of file"));
    done += static_cast<std::size_t>(n);
  }
}

void zeroTableMemory(void* data, std::size_t bytes) {
  constexpr std::size_t kBlock = std::size_t{2} << 20;
  const long long blocks = static_cast<long long>((bytes + kBlock - 1) / kBlock);
  auto* p = static_cast<unsigned char*>(data);
#pragma omp parallel for schedule(static)
  for (long long i = 0; i < blocks; ++i) {
    const std::size_t from = static_cast<std::size_t>(i) * kBlock;
    std::memset(p + from, 0, std::min(kBlock, bytes - from));
  }
}

std::size_t AtmosphereTables::bytes() const {
  std::size_t n = multipleScattering.values.size();
  for (const FloatTable3D& t : singleScattering) n += t.values.size();
  return n * sizeof(float) +
         (transmittance.values.size() + directIrradiance.values.size() + irradiance.values.size()) * sizeof(double);
}

namespace {

// ---- one batch of wavelengths ---------------------------------------------------------------

/// One batch of wavelengths: its stages in order (atmosphere/precompute/Batch.hpp). The 3D
/// tables go straight into `single` and `multiple` from channel l0 on. With a sink, they
/// are the batch's own: the single scattering goes to the sink once finished and is freed
/// after the second order's density and irradiance (the last to read it); `multiple` is
/// made (from empty, spilled with o.spillTables) then, and goes to the sink at the end, J_k
/// freed first. transmittanceColumns (or null): the straight rays' column densities, made
/// by the first batch and read by the next.
BatchResult computeBatch(const Atmosphere& atm, const PrecomputeOptions& o, Runner& run,
                         std::vector<FloatTable3D>& single, FloatTable3D& multiple, int l0,
                         const BatchTablesSink& sink, std::vector<double>* transmittanceColumns) {
  Batch batch(atm, o, run, single, multiple, l0);
  batch.transmittanceColumns = transmittanceColumns;
  const auto handOnSingle = [&] {
    if (!sink) return;
    for (std::size_t q = 0; q < single.size(); ++q) {
      single[q].populate(0, single[q].depth);  // spilled: in one call, not a page fault each
      sink(l0, static_cast<int>(q), single[q]);
      single[q].releaseAll();
    }
  };
  const auto freeSingle = [&] {
    if (!sink) return;
    for (FloatTable3D& s : single) FloatTable3D().values.swap(s.values);
  };
  const auto handOnMultiple = [&] {
    if (!sink) return;
    FloatTable3D().values.swap(batch.density.values);
    FloatTable3D().values.swap(batch.delta.values);
    if (multiple.values.empty()) multiple.resize(batch.W, batch.MU, batch.R, batch.nl, o.spillTables);  // one order: zeros
    multiple.populate(0, multiple.depth);
    sink(l0, static_cast<int>(single.size()), multiple);
    FloatTable3D().values.swap(multiple.values);
  };
  computeTransmittance(batch);
  computeDirectIrradiance(batch);
  if (batch.ownMultipleScatteringRays() && o.orders > 1)
    buildViewRays(batch, o.multipleScatteringSamples, batch.multipleRays);
  computeSingleScattering(batch);
  handOnSingle();
  if (o.orders < 2) {
    freeSingle();
    handOnMultiple();
    return std::move(batch.out);
  }

  batch.density.resize(batch.W, batch.MU, batch.R, batch.nl);
  prepareDensityDirections(batch);
  batch.nextE.resize(batch.IW, batch.IH, batch.nl);
  for (int order = 2; order <= o.orders; ++order) {
    computeScatteringDensity(batch, order);
    computeIndirectIrradiance(batch, order);
    if (order == 2) {  // L_1 is read no more; L_2 on
      freeSingle();
      batch.delta.resize(batch.W, batch.MU, batch.R, batch.nl, o.spillTables);
      if (multiple.values.empty()) multiple.resize(batch.W, batch.MU, batch.R, batch.nl, o.spillTables);
    }
    batch.deltaE = batch.nextE;
    computeMultipleScattering(batch);
    batch.out.orderMean.push_back(batch.meanOf(
        [&](int x, int y, int z, double* v) { std::copy_n(batch.delta.at(x, y, z), batch.nl, v); },
        [&, reading = SliceWindow(batch.incomingTables(2))](int z) mutable { reading(z + 1, z + 2); }));
  }
  handOnMultiple();
  return std::move(batch.out);
}

Atmosphere subAtmosphere(const Atmosphere& atm, const std::vector<int>& ls) {
  Atmosphere s = atm;
  auto pick = [&](const std::vector<double>& v) {
    std::vector<double> r;
    for (int l : ls) r.push_back(v[l]);
    return r;
  };
  s.wavelengthsNm = pick(atm.wavelengthsNm);
  s.groundAlbedo = pick(atm.groundAlbedo);
  for (std::size_t c = 0; c < atm.components.size(); ++c) {
    const Component& a = atm.components[c];
    Component& d = s.components[c];
    d.scatteringPerM = pick(a.scatteringPerM);
    d.absorptionPerM = pick(a.absorptionPerM);
    d.phases.clear();
    for (int l : ls) d.phases.push_back(a.phases.at(l));
  }
  return s;
}

void copyChannels2D(const Table2D& from, Table2D& to, const std::vector<int>& ls) {
  const std::size_t n = static_cast<std::size_t>(from.width) * from.height;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < ls.size(); ++k) to.values[i * to.channels + ls[k]] = from.values[i * from.channels + k];
}
}  // namespace

ScatteringCoords scatteringCoordsFromRMuMuSNu(const ShellRadii& shell, const ScatteringTableSize& size,
                                              double muSMin, double r, double mu, double muS, double nu,
                                              bool rayIntersectsGround) {
  const ScatterGeometry g(shell, size, muSMin);
  return {ScatterGeometry::uNu(nu), g.uMuS(muS), g.uMu(r, mu, rayIntersectsGround), g.uR(r)};
}

ScatteringPoint rMuMuSNuFromScatteringCoords(const ShellRadii& shell, const ScatteringTableSize& size,
                                             double muSMin, const ScatteringCoords& c) {
  const ScatterGeometry g(shell, size, muSMin);
  ScatteringPoint p;
  p.r = g.rFromU(c.uR);
  p.mu = g.muFromU(p.r, c.uMu, p.rayIntersectsGround);
  p.muS = g.muSFromU(c.uMuS);
  p.nu = clampCosine(2.0 * c.uNu - 1.0);
  return p;
}

ScatteringPoint scatteringTexelPoint(const ShellRadii& shell, const ScatteringTableSize& size, double muSMin,
                                     int x, int y, int z) {
  return ScatterGeometry(shell, size, muSMin).texel(x, y, z);
}

// ---- precompute ------------------------------------------------------------------------------

std::size_t batchBytesPerWavelength(const PrecomputeOptions& o, int scatterers) {
  const std::size_t table = static_cast<std::size_t>(o.scatteringNu) * o.scatteringMuS * o.scatteringMu *
                            o.scatteringR * sizeof(float);
  const std::size_t ns = static_cast<std::size_t>(scatterers);
  if (o.spillTables) {  // J_k (or a table the sink reads) whole; slices of the single scattering, or of L_k and the sum
    const std::size_t slices = std::min<std::size_t>(kSpilledSlices, static_cast<std::size_t>(o.scatteringR));
    return table + std::max<std::size_t>(ns, 2) * (table / o.scatteringR) * slices;
  }
  return (o.orders < 2 ? ns + 1 : std::max<std::size_t>(ns + 1, 3)) * table;
}

int wavelengthBatchFor(const PrecomputeOptions& o, int scatterers, int wavelengths, std::size_t budgetBytes) {
  const std::size_t per = std::max<std::size_t>(1, batchBytesPerWavelength(o, scatterers));
  const int n = std::max(1, wavelengths);
  const int fit = static_cast<int>(std::clamp<std::size_t>(budgetBytes / per, 1, static_cast<std::size_t>(n)));
  const int batches = (n + fit - 1) / fit;
  return (n + batches - 1) / batches;  // as even as the batches can be: 47 in 16 + 16 + 15, not 22 + 22 + 3
}

int densityDirectionsFor(const Atmosphere& atmosphere) {
  double halfWidthRad = kPi / 2;  // of the narrowest forward peak
  const std::size_t nl = atmosphere.wavelengthsNm.size();
  // Each component's share of the scattering optical depth per wavelength: one below
  // kMinDensityShare (the coarse sea salt of a maritime aerosol, the insoluble dust of a
  // continental one) adds at most that share of the light its peak would need resolving.
  std::vector<double> column, total(nl, 0.0);
  for (const Component& c : atmosphere.components) {
    column.push_back(c.density.integral(0.0, atmosphere.thicknessM()));
    for (std::size_t l = 0; l < nl; ++l) total[l] += column.back() * c.scatteringPerM[l];
  }
  for (std::size_t i = 0; i < atmosphere.components.size(); ++i) {
    const Component& c = atmosphere.components[i];
    if (!c.scatters()) continue;
    for (std::size_t l = 0; l < nl; ++l) {
      const double share = column[i] * c.scatteringPerM[l] / total[l];
      if (share < kMinDensityShare) continue;
      // The peak's half width: where p falls to half its value at the peak's start. A spike
      // whose light (its share of the component's, times the component's share) is below
      // kMinDensityShare is passed over, as a minor component is: the coarse particles of a
      // mixture narrow its phase function's tip but carry little of its light.
      const PhaseFunction& p = c.phase(l);
      constexpr double kStepDeg = 0.05, kStepRad = kStepDeg * kPi / 180.0;
      double start = p(1.0), inside = 0.0;  // inside: 2 pi int p dOmega from 0 to deg
      for (double deg = kStepDeg; deg < halfWidthRad * 180.0 / kPi; deg += kStepDeg) {
        const double theta = deg * kPi / 180.0, value = p(std::cos(theta));
        inside += 2.0 * kPi * value * std::sin(theta) * kStepRad;
        if (value > 0.5 * start) continue;
        if (share * inside >= kMinDensityShare) {
          halfWidthRad = theta;
          break;
        }
        start = value;  // a faint spike: look on for the lobe under it
      }
    }
  }
  const int n = static_cast<int>(std::ceil(kPi / (1.5 * halfWidthRad) / 8.0)) * 8;
  return std::clamp(n, kMinDensityDirections, 64);
}

AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& optionsIn,
                            const PrecomputeProgress& progress) {
  return precompute(atmosphere, optionsIn, progress, BatchTablesSink());
}

AtmosphereTables precompute(const Atmosphere& atmosphere, const PrecomputeOptions& optionsIn,
                            const PrecomputeProgress& progress, const BatchTablesSink& sink) {
  if (const std::string e = optionsIn.validate(); !e.empty()) throw std::invalid_argument("PrecomputeOptions: " + e);
  if (const std::string e = atmosphere.validate(); !e.empty()) throw std::invalid_argument("Atmosphere: " + e);
  PrecomputeOptions options = optionsIn;
  if (options.sphereSamples == 0) options.sphereSamples = densityDirectionsFor(atmosphere);
  const int nl = static_cast<int>(atmosphere.wavelengthsNm.size());
  if (nl == 0) throw std::invalid_argument("Atmosphere: no wavelengths");
  const auto t0 = std::chrono::steady_clock::now();

  AtmosphereTables tables;
  tables.options = options;
  tables.bottomRadiusM = atmosphere.bottomRadiusM;
  tables.topRadiusM = atmosphere.topRadiusM;
  tables.wavelengthsNm = atmosphere.wavelengthsNm;
  for (const Component& c : atmosphere.components)
    if (c.scatters()) tables.scatteringComponents.push_back(c.name);

  const int batch = options.wavelengthBatch > 0 ? std::min(options.wavelengthBatch, nl) : nl;
  const int batches = (nl + batch - 1) / batch;
  std::map<std::string, double> timings;
  std::vector<std::string> order;
  const int orders = options.orders;
  const double weight = 1.0 + 0.05 + 0.3 * (options.multipleScatteringSamples != options.singleScatteringSamples ? 1 : 0) +
                        1.3 + (orders - 1) * (2.0 + 0.1 + 1.0);
  const int W = options.scatteringNu * options.scatteringMuS;
  // The 4D tables: all wavelengths wide, or (with a sink) one batch's single scattering,
  // handed on (computeBatch makes the batch's multiple scattering when it needs it).
  auto sizeSingle = [&](std::vector<FloatTable3D>& single, int channels, bool spill) {
    single.resize(tables.scatteringComponents.size());
    for (FloatTable3D& T : single) T.resize(W, options.scatteringMu, options.scatteringR, channels, spill);
  };
  if (!sink) {
    sizeSingle(tables.singleScattering, nl, false);
    tables.multipleScattering.resize(W, options.scatteringMu, options.scatteringR, nl);
  }
  bool first = true;  // the first batch this process computes sizes the 2D tables
  std::vector<double> transmittanceColumns;  // shared by the batches (computeBatch)
  for (int bi = 0; bi < batches; ++bi) {
    if (bi % options.batchShareCount != options.batchShareIndex) continue;
    std::vector<int> ls;
    for (int l = bi * batch; l < std::min(nl, (bi + 1) * batch); ++l) ls.push_back(l);
    Runner runner(progress, options.threads, static_cast<double>(bi) / batches, static_cast<double>(bi + 1) / batches);
    runner.setStages(weight);
    std::vector<FloatTable3D> batchSingle;
    FloatTable3D batchMultiple;
    if (sink) sizeSingle(batchSingle, static_cast<int>(ls.size()), options.spillTables);
    BatchResult r = computeBatch(
        batches == 1 ? atmosphere : subAtmosphere(atmosphere, ls), options, runner,
        sink ? batchSingle : tables.singleScattering, sink ? batchMultiple : tables.multipleScattering,
        sink ? 0 : ls.front(),
        sink ? BatchTablesSink([&](int, int table, const FloatTable3D& v) { sink(ls.front(), table, v); })
             : BatchTablesSink(),
        batches > 1 ? &transmittanceColumns : nullptr);
    if (batches == 1) {
      tables.transmittance = std::move(r.transmittance);
      tables.directIrradiance = std::move(r.directIrradiance);
      tables.irradiance = std::move(r.irradiance);
      tables.orderMeanRadiance = std::move(r.orderMean);
    } else {
      if (first) {
        auto size2 = [&](Table2D& d, const Table2D& s) { d.resize(s.width, s.height, nl); };
        size2(tables.transmittance, r.transmittance);
        size2(tables.directIrradiance, r.directIrradiance);
        size2(tables.irradiance, r.irradiance);
        tables.orderMeanRadiance.assign(r.orderMean.size(), std::vector<double>(nl, 0.0));
      }
      copyChannels2D(r.transmittance, tables.transmittance, ls);
      copyChannels2D(r.directIrradiance, tables.directIrradiance, ls);
      copyChannels2D(r.irradiance, tables.irradiance, ls);
      for (std::size_t k = 0; k < r.orderMean.size(); ++k)
        for (std::size_t i = 0; i < ls.size(); ++i) tables.orderMeanRadiance[k][ls[i]] = r.orderMean[k][i];
    }
    for (const std::string& s : runner.order) {
      if (std::find(order.begin(), order.end(), s) == order.end()) order.push_back(s);
      timings[s] += runner.timings[s];
    }
    first = false;
  }
  for (const std::string& s : order) tables.timings.push_back({s, timings[s]});
  tables.timings.push_back({"total", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
  if (progress && !progress(1.0, "done")) throw PrecomputeCancelled();
  return tables;
}

// ---- lookups ---------------------------------------------------------------------------------

void transmittanceToTop(const AtmosphereTables& tables, double r, double mu, double* out) {
  lookupTransmittance(tables.transmittance, tables.shell(), r, mu, out);
}

std::vector<double> transmittanceToTop(const AtmosphereTables& tables, double r, double mu) {
  std::vector<double> v(tables.wavelengthCount());
  transmittanceToTop(tables, r, mu, v.data());
  return v;
}

std::vector<double> lookupScattering(const AtmosphereTables& tables, const FloatTable3D& table, double r, double mu,
                                     double muS, double nu, bool rayIntersectsGround) {
  const ScatterGeometry g = geometryOf(tables);
  std::vector<double> v(table.channels, 0.0);
  accumulate4(table, rMuCell(g, r, mu, rayIntersectsGround), sNuCell(g, muS, nu), 1.0, v.data());
  return v;
}

std::vector<double> transmittanceAlong(const AtmosphereTables& tables, double r, double mu, double d,
                                       bool rayIntersectsGround, bool endsOnGround) {
  const double b = tables.bottomRadiusM;
  const double rd = endsOnGround ? b : std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
  const double mud = clampCosine((r * mu + d) / rd);
  const std::vector<double> a = rayIntersectsGround ? transmittanceToTop(tables, rd, -mud) : transmittanceToTop(tables, r, mu);
  const std::vector<double> c = rayIntersectsGround ? transmittanceToTop(tables, r, -mu) : transmittanceToTop(tables, rd, mud);
  std::vector<double> out(a.size());
  for (std::size_t l = 0; l < a.size(); ++l) out[l] = std::min(a[l] / std::max(c[l], 1e-300), 1.0);
  return out;
}

namespace {

/// skyRadiance's table lookups at a Sun within the tables (muS >= muSMin): lookupScattering
/// in each table, the cell found once for all of them; adds to L (one value per wavelength).
/// phasesOf(q, nu, P): the phase function of single-scattering table q at each wavelength,
/// into P[0 .. wavelengths).
template <class PhasesOf>
void addTableRadiance(const AtmosphereTables& tables, const ScatterGeometry& g, const PhasesOf& phasesOf, double r,
                      double mu, double muS, double nu, bool ground, double* L) {
  const RMuCell a = rMuCell(g, r, mu, ground);
  const SNuCell c = sNuCell(g, muS, nu);
  const std::size_t nl = tables.wavelengthCount();
  accumulate4(tables.multipleScattering, a, c, 1.0, L);
  constexpr std::size_t kStack = 64;  // no allocation for up to this many wavelengths
  std::array<double, 2 * kStack> stack;
  std::vector<double> heap(nl > kStack ? 2 * nl : 0);
  double* S = nl > kStack ? heap.data() : stack.data();
  double* P = S + nl;
  for (std::size_t q = 0; q < tables.singleScattering.size(); ++q) {
    std::fill(S, S + nl, 0.0);
    accumulate4(tables.singleScattering[q], a, c, 1.0, S);
    phasesOf(q, nu, P);
    for (std::size_t l = 0; l < nl; ++l) L[l] += S[l] * P[l];
  }
}

/// skyRadiance per unit solar irradiance into L, with the tables' geometry and phases given.
template <class PhasesOf>
void skyRadianceWith(const AtmosphereTables& tables, const ScatterGeometry& g, const PhasesOf& phasesOf, double r,
                     double mu, double muS, double nu, double* L) {
  const int nl = static_cast<int>(tables.wavelengthCount());
  const double b = tables.bottomRadiusM, muSMin = tables.options.muSMin;
  const bool ground = rayIntersectsGround(b, r, mu);
  std::fill(L, L + nl, 0.0);
  if (muS >= muSMin) return addTableRadiance(tables, g, phasesOf, r, mu, muS, nu, ground, L);
  const double end = ground ? distanceToBottomBoundaryM(b, r, mu) : distanceToTopBoundaryM(tables.topRadiusM, r, mu);
  const double d = distanceToSunCosineM(r, mu, muS, nu, muSMin);
  if (!(d < end)) return;
  const double rd = std::clamp(std::sqrt(d * d + 2.0 * r * mu * d + r * r), b, tables.topRadiusM);
  addTableRadiance(tables, g, phasesOf, rd, clampCosine((r * mu + d) / rd), muSMin, nu, ground, L);
  const std::vector<double> T = transmittanceAlong(tables, r, mu, d, ground);
  for (int l = 0; l < nl; ++l) L[l] *= T[l];
}

}  // namespace

void skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu, double muS,
                 double nu, double* L) {
  auto phasesOf = [&](std::size_t q, double c, double* P) {
    const Component& component = atmosphere.component(tables.scatteringComponents[q]);
    for (std::size_t l = 0; l < tables.wavelengthCount(); ++l) P[l] = component.phase(l)(c);
  };
  skyRadianceWith(tables, geometryOf(tables), phasesOf, r, mu, muS, nu, L);
}

SkyRadianceLookup::SkyRadianceLookup(const AtmosphereTables& tables, const Atmosphere& atmosphere)
    : tables_(tables), geometry_(std::make_shared<const ScatterGeometry>(geometryOf(tables))) {
  const std::size_t nl = tables.wavelengthCount();
  for (const std::string& name : tables.scatteringComponents) {
    const Component& component = atmosphere.component(name);
    bool shared = nl > 0;
    for (std::size_t l = 0; l < nl; ++l) {
      const PhaseFunction& p = component.phase(l);
      phases_.push_back(&p);
      shared = shared && p.kind() == PhaseFunction::Kind::Tabulated &&
               p.cosThetaSamples() == component.phase(0).cosThetaSamples();
    }
    sharedSamples_.push_back(shared);
  }
}

void SkyRadianceLookup::operator()(double r, double mu, double muS, double nu, double* L) const {
  const std::size_t nl = tables_.wavelengthCount();
  auto phasesOf = [&](std::size_t q, double c, double* P) {
    const PhaseFunction* const* p = phases_.data() + q * nl;
    if (sharedSamples_[q]) {  // one search for every wavelength's table
      const PhaseFunction::Interval s = p[0]->interval(c);
      for (std::size_t l = 0; l < nl; ++l) P[l] = p[l]->valueIn(s);
    } else {
      for (std::size_t l = 0; l < nl; ++l) P[l] = (*p[l])(c);
    }
  };
  skyRadianceWith(tables_, *geometry_, phasesOf, r, mu, muS, nu, L);
}

std::vector<double> skyRadiance(const AtmosphereTables& tables, const Atmosphere& atmosphere, double r, double mu,
                                double muS, double nu, const std::vector<double>& solarIrradiance) {
  const int nl = static_cast<int>(tables.wavelengthCount());
  std::vector<double> L(nl);
  skyRadiance(tables, atmosphere, r, mu, muS, nu, L.data());
  if (!solarIrradiance.empty())
    for (int l = 0; l < nl; ++l) L[l] *= solarIrradiance.at(l);
  return L;
}

std::vector<double> indirectIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount(), 0.0);
  if (muS < tables.options.muSMin) return v;
  lookupIrradiance(tables.irradiance, tables.shell(), r, muS, v.data());
  return v;
}

double sunDiscCosine(double muS, double alphaRad) {
  if (muS < -alphaRad) return 0.0;
  if (muS > alphaRad) return muS;
  return (muS + alphaRad) * (muS + alphaRad) / (4.0 * alphaRad);
}

std::vector<double> directIrradiance(const AtmosphereTables& tables, double r, double muS) {
  std::vector<double> v(tables.wavelengthCount());
  directIrradianceAt(tables.transmittance, tables.shell(), tables.options.sunAngularRadiusRad, r, muS, v.data());
  return v;
}

}  // namespace umbra::atmosphere
