#include "MapFiles.h"

#include "AlbedoMap.hpp"
#include "MilkyWay.hpp"
#include "StarCatalogueCache.h"
#include "Colour.hpp"
#include "Spectrum.hpp"   // srgbToLinear

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkImageReader2Factory.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedShortArray.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace umbra::pipeline {
namespace {

// Reads a map's image (`what`: "albedo map", "normal map"): 8- or 16-bit values,
// `range` their largest. Throws std::invalid_argument naming the file.
vtkSmartPointer<vtkImageData> readMapImage(const std::string& path, const std::string& what, double& range) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::invalid_argument(what + " '" + path + "': no such file");
  vtkSmartPointer<vtkImageReader2> reader;
  reader.TakeReference(vtkImageReader2Factory::CreateImageReader2(path.c_str()));
  if (!reader) throw std::invalid_argument(what + " '" + path + "': not an image VTK reads (JPEG, PNG, TIFF)");
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (reader->GetErrorCode() != 0 || !scalars || dims[0] < 2 || dims[1] < 2 || dims[2] != 1)
    throw std::invalid_argument(what + " '" + path + "': cannot read a 2D image from it");
  range = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 255.0 : scalars->GetDataType() == VTK_UNSIGNED_SHORT ? 65535.0 : 0.0;
  if (range == 0.0) throw std::invalid_argument(what + " '" + path + "': needs 8- or 16-bit values");
  return image;
}

// A grey albedo map: its grey values (the luminance of a colour image), its small dark
// marks and holes filled in (sky::darkSpots, sky::fillGaps), and the mean that
// sky::nearSideDiscMean gives of them.
std::shared_ptr<MapTexels> relativeAlbedoTexels(const std::string& path, vtkImageData* image, double range) {
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const int comps = scalars->GetNumberOfComponents();
  sky::AlbedoMap map;
  map.width = dims[0];
  map.height = dims[1];
  map.values.resize(static_cast<std::size_t>(dims[0]) * dims[1]);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(map.values.size()); ++i) {
    const double y = comps >= 3 ? colour::luminance({scalars->GetComponent(i, 0), scalars->GetComponent(i, 1),
                                                      scalars->GetComponent(i, 2)})
                                : scalars->GetComponent(i, 0);
    map.values[i] = static_cast<float>(std::round(y / range * 255.0) / 255.0);
  }
  sky::fillGaps(map, sky::darkSpots(map));
  auto grey = vtkSmartPointer<vtkUnsignedCharArray>::New();
  grey->SetNumberOfComponents(1);
  grey->SetNumberOfTuples(static_cast<vtkIdType>(map.values.size()));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(map.values.size()); ++i) {
    const auto byte = static_cast<unsigned char>(std::clamp(std::lround(map.values[i] * 255.0), 0L, 255L));
    map.values[i] = byte / 255.0f;  // what the texture holds
    grey->SetValue(i, byte);
  }
  sky::validate(map, ("albedo map '" + path + "'").c_str());
  auto out = std::make_shared<MapTexels>();
  out->discMean = sky::nearSideDiscMean(map);
  out->width = map.width;
  out->height = map.height;
  if (!(out->discMean > 0.0))
    throw std::invalid_argument("albedo map '" + path + "': black over the disc seen from longitude 0, latitude 0");
  auto texels = vtkSmartPointer<vtkImageData>::New();
  texels->SetDimensions(dims[0], dims[1], 1);
  texels->GetPointData()->SetScalars(grey);
  out->texels = texels;
  return out;
}

// RGB texels: as they are (8-bit), or their sRGB decoded to linear values (16-bit).
std::shared_ptr<MapTexels> rgbTexels(const std::string& path, const char* what, const char* channels,
                                     vtkImageData* image, double range, bool decodeSrgb) {
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (scalars->GetNumberOfComponents() < 3)
    throw std::invalid_argument(std::string(what) + " '" + path + "': needs RGB (" + channels + "), got " +
                                std::to_string(scalars->GetNumberOfComponents()) + " channel(s)");
  vtkSmartPointer<vtkDataArray> rgb;
  if (decodeSrgb) rgb = vtkSmartPointer<vtkUnsignedShortArray>::New();
  else rgb = vtkSmartPointer<vtkUnsignedCharArray>::New();
  const double top = decodeSrgb ? 65535.0 : 255.0;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(scalars->GetNumberOfTuples());
  for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double v = scalars->GetComponent(i, c) / range;
      rgb->SetComponent(i, c, std::round((decodeSrgb ? atmosphere::srgbToLinear(v) : v) * top));
    }
  auto out = std::make_shared<MapTexels>();
  out->texels = vtkSmartPointer<vtkImageData>::New();
  out->texels->SetDimensions(dims[0], dims[1], 1);
  out->texels->GetPointData()->SetScalars(rgb);
  out->width = dims[0];
  out->height = dims[1];
  return out;
}

}  // namespace

std::shared_ptr<const MapTexels> mapTexels(const std::string& path, MapKind kind) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, MapKind>, std::shared_ptr<const MapTexels>> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto it = loaded.find({path, kind}); it != loaded.end()) return it->second;
  const char* what = kind == MapKind::Normals ? "normal map" : "albedo map";
  double range = 0.0;
  vtkSmartPointer<vtkImageData> image = readMapImage(path, what, range);
  std::shared_ptr<MapTexels> out;
  if (kind == MapKind::RelativeAlbedo) {
    out = relativeAlbedoTexels(path, image, range);
  } else {
    const bool reflectance = kind == MapKind::Reflectance;
    out = rgbTexels(path, what, reflectance ? "a colour" : "east, south, up", image, range, reflectance);
  }
  loaded[{path, kind}] = out;
  return out;
}

std::shared_ptr<const MilkyWayTexels> milkyWayTexels(const std::string& path, const std::string& cataloguePath,
                                                     double removedToV) {
  static std::mutex mutex;
  static std::map<std::tuple<std::string, std::string, double>, std::shared_ptr<const MilkyWayTexels>> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_tuple(path, cataloguePath, removedToV);
  if (auto it = loaded.find(key); it != loaded.end()) return it->second;
  double range = 0.0;
  vtkSmartPointer<vtkImageData> image = readMapImage(path, "Milky Way map", range);
  const std::shared_ptr<MapTexels> texels = rgbTexels(path, "Milky Way map", "a colour", image, range, true);
  vtkDataArray* values = texels->texels->GetPointData()->GetScalars();
  sky::MilkyWayMap map;
  map.width = texels->width;
  map.height = texels->height;
  map.rgb.resize(static_cast<std::size_t>(map.width) * map.height * 3);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    for (int c = 0; c < 3; ++c) map.rgb[3 * i + c] = static_cast<float>(values->GetComponent(i, c) / 65535.0);
  if (!cataloguePath.empty()) {
    std::vector<glm::dvec3> places;
    std::vector<double> vMags;
    for (const sky::CatalogueStar& star : *starCatalogue(cataloguePath)) {
      if (!(star.vMag <= removedToV)) continue;
      places.push_back(sky::icrsDirection(star.raRad, star.decRad));
      vMags.push_back(star.vMag);
    }
    sky::removeStars(map, places, vMags);
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double q = std::round(std::clamp(static_cast<double>(map.rgb[3 * i + c]), 0.0, 1.0) * 65535.0);
        values->SetComponent(i, c, q);
        map.rgb[3 * i + c] = static_cast<float>(q / 65535.0);  // what the texture holds
      }
  }
  auto out = std::make_shared<MilkyWayTexels>();
  try {
    out->radiancePerSunIrradiance = sky::milkyWayRadianceScale(map, 1.0);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("Milky Way map '" + path + "': " + e.what());
  }
  out->sphereMeanRadiancePerSunIrradiance = out->radiancePerSunIrradiance * sky::sphereMeanLuminance(map);
  out->map = texels;
  loaded[key] = out;
  return out;
}

}  // namespace umbra::pipeline
