#pragma once
// AtmosphereModel: an atmosphere as the user named it (a preset, a file, or the text of an
// editor), read, resolved ("extends") and checked once, where it is named (a CLI option, a
// scene, the GUI), then passed down as a value: the scene, the pipeline and the filters
// take it instead of a name to read again. Its Atmosphere at a set of wavelengths is built
// the first time it is asked for and kept.
#include "Atmosphere.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace umbra::atmosphere {

class AtmosphereModel {
 public:
  /// A preset name or a file's path (loadAtmosphere's rules). Reads and checks it (built at
  /// the R, G, B wavelengths, which every renderer uses). Throws AtmosphereError with a
  /// one-line message.
  static std::shared_ptr<const AtmosphereModel> load(const std::string& presetNameOrPath);
  /// The same from JSON text (parseAtmosphere's rules); `sourceName` names it in messages
  /// and is its name(); a relative "extends" is looked for in `baseDirectory`.
  static std::shared_ptr<const AtmosphereModel> fromText(const std::string& jsonText, const std::string& sourceName,
                                                         const std::string& baseDirectory = ".");

  /// How the user named it: the preset name or the path as given (or the editor's source).
  const std::string& name() const { return name_; }
  /// The model at these wavelengths, built on first use and kept (thread-safe). Throws
  /// AtmosphereError as loadAtmosphere does (a formula outside its range there).
  const Atmosphere& at(const std::vector<double>& wavelengthsNm) const;
  /// The model at R, G, B (680, 550, 440 nm).
  const Atmosphere& rgb() const;
  /// Its JSON document with "extends" resolved, as text (resolvedAtmosphereJson's).
  std::string resolvedJson() const;

  /// How many documents AtmosphereModel, loadAtmosphere and parseAtmosphere have read and
  /// resolved in this process: what a test counts to see that a run reads its atmosphere
  /// once.
  static long documentsRead();

  struct Document;  ///< the resolved JSON document (AtmosphereReader.cpp)
  AtmosphereModel(std::string name, std::shared_ptr<const Document> doc);

 private:
  std::string name_;
  std::shared_ptr<const Document> doc_;
  mutable std::mutex mutex_;
  mutable std::map<std::vector<double>, std::unique_ptr<const Atmosphere>> built_;
};

using AtmosphereModelPtr = std::shared_ptr<const AtmosphereModel>;

/// The model named `name` (a preset or a file): `kept` when it is that one, else the name
/// read (AtmosphereModel::load) and kept there; null for "". What a filter given a name
/// rather than a model does, so that it reads the name once while it stays.
AtmosphereModelPtr modelNamed(const std::string& name, AtmosphereModelPtr& kept);

}  // namespace umbra::atmosphere
