#pragma once
// The glue from a scene to the renderer (the CLI and the GUI share it): what the renderer
// needs from a scene (the Sun as the light, the other bodies as spheres, each a receiver
// shadowed by the rest, and the camera), and the table sources configured for it.
#include "AtmosphereModel.hpp"
#include "BodyView.h"
#include "EclipseShading.h"
#include "MapFiles.h"

#include <optional>
#include <string>
#include <vector>

class vtkAtmosphereTablesSource;

namespace umbra::scene { struct Scene; }

namespace umbra::pipeline {

// The renderer's types that the glue fills.
using render::AtmosphereRendering;
using render::BodyView;
using render::EclipseShading;
using render::SphereBody;
using render::StarPoint;
using render::SunLight;
using render::ViewCamera;

/// The atmosphere a scene asks to draw (scene::Body::atmosphere).
struct SceneAtmosphere {
  std::string body;  ///< the body it surrounds (its SphereBody has the same name)
  atmosphere::AtmosphereModelPtr model;  ///< the scene's, read once with it (never null)
  /// The model's ground and top radii (sceneInputs sets them; 0: not known, the body's
  /// sphere and the model are read where needed). The eclipse tables are made for the
  /// ground radius, not for the body's sphere, which an observer on it may shrink.
  double bottomRadiusM = 0.0, topRadiusM = 0.0;
  /// The model's vertical optical depth from the ground to the top at 550 nm.
  double zenithOpticalDepth550 = 0.0;
  /// At night (the Sun's centre below the camera's horizon, the camera in the air), the
  /// Moon's light on the sky and the ground: its position and its irradiance at the camera
  /// per channel (sky::apparentMagnitudeV for its phase and distances, times the eclipse
  /// factor at its centre, in its colour); zero by day or without a Moon above -5 deg.
  glm::dvec3 moonPositionM{0.0}, moonIrradianceWm2{0.0};
  /// The night sky's glow above an Earth atmosphere (AtmosphereRendering::SetNightGlow;
  /// sky::nightGlowAboveAirWm2Sr for zenithOpticalDepth550 and the Milky Way map's mean
  /// over the sphere when it is drawn); 0 for other bodies.
  double nightGlowWm2Sr = 0.0;
  /// The body's cloud layers as drawn (scene::Body::clouds): the noise fixed to the body (its rotation model, with a time; else the world's axes) and
  /// turned by the wind since the file's time; and the eclipse at the camera (the other
  /// bodies' shadow), which dims the direct sunlight on them.
  std::vector<AtmosphereRendering::CloudLayerView> clouds{};
  glm::dvec3 cloudSunFactor{1.0};
  /// The body's reflectance map ("bluemarble"), drawn as the ground's albedo by the
  /// composite (AtmosphereRendering::SetGroundAlbedoMap; its receiver is then white); null for none.
  std::shared_ptr<const render::MapTexels> groundAlbedoMap{};
};

struct SceneInputs {
  SunLight sun;
  std::vector<SphereBody> bodies;
  ViewCamera camera;
  std::optional<SceneAtmosphere> atmosphere;
  /// The scene's stars to its limiting magnitude (none without "stars"): apparent places for
  /// the camera at the scene's time (scene::starObserverOf), irradiance for this Sun.
  std::vector<StarPoint> stars;
  /// The Milky Way behind them (the scene's stars.milkyWayPath; none without): the map with
  /// the stars it shows and the scene draws taken out, and the factor to frame radiance for
  /// this Sun.
  std::shared_ptr<const MilkyWayTexels> milkyWay;
  double milkyWayRadianceScale = 0.0;
};

/// The scene at its current time. A body's albedo is 3/2 of its geometric albedo, for
/// Lambert's law (exact for a Lambertian sphere) and for Hapke's (A = p / I(0), I(0) = 2/3),
/// tinted by its colour (its reflectance at 680, 550, 440 nm: sky::reflectanceTint) at equal
/// luminance; it keeps its photometry, its albedo and normal maps (their texels, read once
/// per process: MapFiles.h; std::invalid_argument naming a file that cannot be read) and its
/// body-fixed frame (with a rotation model), and a Hapke body is lit by the Earth too
/// (earthshine) when the scene has one.
/// The stars come from the scene's catalogue (read once per process, from the table cache's
/// binary copy when there is one: StarCatalogueCache.h).
/// A body whose sphere would enclose the camera (an observer near a pole, below the mean
/// radius) is shrunk to just below the camera.
///
/// A body with an atmosphere to draw (at most one per scene; std::invalid_argument
/// otherwise) is a sphere of the atmosphere's bottom radius (the ground of its tables),
/// and an observer standing on it is placed at that radius plus its altitude (at least
/// 1 m), in the same direction from the centre; the target moves with it.
SceneInputs sceneInputs(const scene::Scene& scene);

/// The sizes of the atmosphere tables a caller asks for: atmosphere::kDefaultTableSizes,
/// or kSmallTableSizes for quick looks and tests (about a second).
enum class AtmosphereTableSizes { Default, Small };

/// What the sky of a scene needs of its tables beyond their sizes. For a camera in the air
/// with the Sun's centre more than 1 deg below its horizon and less than 10 deg past the
/// depression 2 acos(bottom / top) at which the top of the atmosphere on the horizon falls
/// into the shadow (twilight: Earth to 30 deg, Mars to 35 deg), tables that resolve the Sun
/// below the horizon and reach below it: four times the mu_s cells in the scattering and
/// the irradiance tables (half the radii for the default sizes, so that the scattering
/// tables are twice as large, not four times), at least 24 density
/// directions, and the lowest Sun 20 deg below the camera's, rounded up to a multiple of
/// 10 deg (so that an animation or the time slider meets few sets), at least 120 deg.
/// Otherwise the day tables, the Sun down to 102 deg: in daylight, with the Sun on the
/// horizon, for a camera above the air, and at night (then the twilight sky is 1e-4 cd/m^2
/// or fainter, below the night sky's own glow, which is not modelled; the day tables draw
/// it black). Why: docs/accuracy-vs-speed/atmosphere-tables.md, "Twilight in the render pass".
struct AtmosphereTableChoice {
  bool twilight = false;
  double lowestSunZenithRad = 0.0;  ///< twilight only (the day tables' is the source's default)
  bool operator==(const AtmosphereTableChoice& o) const {
    return twilight == o.twilight && lowestSunZenithRad == o.lowestSunZenithRad;
  }
  bool operator!=(const AtmosphereTableChoice& o) const { return !(*this == o); }
};
AtmosphereTableChoice atmosphereTableChoice(const SceneInputs& in);

/// Sets every size, the orders, the lowest Sun and the density directions of `source`
/// for `sizes` and `choice` (not the atmosphere, wavelengths, tables nor refraction).
void configureAtmosphereTables(vtkAtmosphereTablesSource* source, AtmosphereTableSizes sizes,
                               const AtmosphereTableChoice& choice = {});

/// Configures `source` for the atmosphere of `in` (std::logic_error without one): its
/// model, 3 wavelengths, the Bruneton tables, `sizes` and the scene's choice
/// (configureAtmosphereTables, atmosphereTableChoice); with `refraction` also the refraction
/// table and the integration along refracted paths.
void configureSceneAtmosphereTables(vtkAtmosphereTablesSource* source, const SceneInputs& in, bool refraction,
                                    AtmosphereTableSizes sizes);

/// Hands the tables of `source`, configured for in.atmosphere, to view.GetAtmosphere()
/// (call after SetBodies): updates it (from its cache, else computed), and with refracted
/// paths the view bends its rays (AtmosphereRendering::SetRefraction). Throws
/// std::runtime_error naming the body when the tables cannot be made. A GUI that computes
/// the tables in a worker configures them there and shows them with this.
void showSceneAtmosphereTables(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source);

/// configureSceneAtmosphereTables then showSceneAtmosphereTables; without an atmosphere,
/// clears the view's.
void applySceneAtmosphere(BodyView& view, const SceneInputs& in, vtkAtmosphereTablesSource* source,
                          bool refraction = false, AtmosphereTableSizes sizes = AtmosphereTableSizes::Default);

/// The night sky of `in` on the view: its stars, and the Moon's light and the night glow
/// on its atmosphere (none without one). Call for every frame, after SetBodies.
void showSceneSky(BodyView& view, const SceneInputs& in);

/// configureAtmosphereTables(source, AtmosphereTableSizes::Small): the day's small tables.
void useSmallAtmosphereTables(vtkAtmosphereTablesSource* source);

} // namespace umbra::pipeline
