#pragma once
// The atmosphere editor: the JSON document of an atmosphere (a preset or a file, its
// "extends" resolved) as a tree of its fields, each with the unit and range that
// atmosphere/Fields.hpp gives it; a type or model is a choice among the table's types (a
// new choice starts with that type's fields). An edited value is checked by the reader
// (atmosphere::parseAtmosphere, the only validator): a bad one is kept in the tree in red
// with the reader's one-line message (file, component and field), the document stays as it
// was; a good one changes the document, and the change callback runs once the edits pause
// (debounced), so that the owner recomputes the tables once for a burst of edits.
#include <QString>
#include <QWidget>

#include <nlohmann/json.hpp>

#include <functional>
#include <string>

class QLabel;
class QTimer;
class QTreeWidget;
class QTreeWidgetItem;

namespace umbra::atmosphere {
struct Field;
}

namespace umbra::gui {

class AtmosphereEditor : public QWidget {
public:
  using Json = nlohmann::ordered_json;

  explicit AtmosphereEditor(QWidget* parent = nullptr);

  /// Shows this (valid) document; `sourceName` is the preset or file it came from. No
  /// change callback. An empty document (Json()) shows "no atmosphere".
  void setDocument(const Json& document, const std::string& sourceName);
  /// The document: the last one the reader accepted.
  const Json& document() const { return this->doc; }
  /// The file the document came from ("" for none).
  const std::string& sourceName() const { return this->source; }
  bool hasDocument() const { return this->doc.is_object(); }

  /// Sets the value at `path` ("components.troposphere.density.scaleHeightM",
  /// "groundAlbedo.values[1]") from text as typed (a number, a JSON array or object; for a
  /// string field, the text itself). An optional key of the field table that the object
  /// lacks ("components.troposphere.densityScale") is added. Returns "" when the reader accepted the document with
  /// it, else the one-line message (also shown, and the text kept in red in the tree).
  std::string setValue(const std::string& path, const std::string& text);
  /// Turns the object at `objectPath` ("components.dust.phase") into `type` (its "type" or
  /// "model"), with the new type's fields (atmosphere::withFieldType). Same return.
  std::string setType(const std::string& objectPath, const std::string& type);
  /// Adds a component with the field table's example profile, optics and phase (an
  /// exponential profile, coefficients, an isotropic phase), or removes one. Same return as setValue.
  std::string addComponent(const std::string& name);
  std::string removeComponent(const std::string& name);
  /// The message of the last rejected edit ("" after an accepted one).
  QString message() const;

  /// Called (debounced, `debounceMs` after the last accepted edit) with the new document.
  void onChanged(std::function<void(const Json&)> callback) { this->changed = std::move(callback); }
  void setDebounceMs(int ms);
  /// Runs a pending change callback now.
  void flush();
  bool changePending() const;

  /// Writes the document as JSON (atomically). Throws std::runtime_error naming the path.
  void saveJson(const std::string& path) const;

  /// The tree (tests look at its items).
  QTreeWidget* tree() const { return this->fields; }

private:
  std::string apply(const std::string& path, Json candidate);  // validate, then accept or reject
  std::string reject(const std::string& path, const std::string& problem);  // red item, message
  void rebuild();
  void scheduleRebuild();  // rebuild() once the event loop runs again
  void addItems(QTreeWidgetItem* parent, const Json& value, const std::string& path, const std::string& where,
                const std::string& type);
  QTreeWidgetItem* itemAt(const std::string& path) const;
  /// The table's description of `path` when it is an optional key its object lacks.
  const atmosphere::Field* optionalField(const std::string& path) const;
  void edited(QTreeWidgetItem* item, int column);
  void describe();  // the components' derived coefficients as tooltips

  Json doc;
  std::string source;
  QTreeWidget* fields = nullptr;
  QLabel* status = nullptr;
  QTimer* debounce = nullptr;
  std::function<void(const Json&)> changed;
  bool building = false;
};

} // namespace umbra::gui
