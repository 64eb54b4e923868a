#include "AtmosphereEditor.hpp"

#include "OutputFile.hpp"

#include "Atmosphere.hpp"
#include "Describe.hpp"
#include "Fields.hpp"
#include "Spectrum.hpp"

#include <QComboBox>
#include <QHeaderView>
#include <QInputDialog>
#include <QLabel>
#include <QMenu>
#include <QTimer>
#include <QTreeWidget>
#include <QTreeWidgetItemIterator>
#include <QVBoxLayout>

#include <algorithm>
#include <fstream>
#include <set>
#include <stdexcept>

namespace umbra::gui {
namespace {

constexpr int kPathRole = Qt::UserRole;
constexpr int kRejectedRole = Qt::UserRole + 1;

QString qs(const std::string& s) { return QString::fromStdString(s); }

/// "components.dust.optics.K.values[1]" -> the JSON pointer /components/dust/optics/K/values/1.
nlohmann::ordered_json::json_pointer pointerOf(const std::string& path) {
  std::string pointer;
  auto key = [&](std::string k) {
    std::string escaped;
    for (char c : k) escaped += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
    pointer += "/" + escaped;
  };
  std::size_t start = 0;
  while (start <= path.size() && !path.empty()) {
    std::size_t dot = path.find('.', start);
    if (dot == std::string::npos) dot = path.size();
    std::string segment = path.substr(start, dot - start);
    const std::size_t bracket = segment.find('[');
    key(segment.substr(0, bracket));
    for (std::size_t b = bracket; b != std::string::npos; b = segment.find('[', b + 1)) {
      const std::size_t close = segment.find(']', b);
      if (close == std::string::npos) throw std::invalid_argument("unbalanced [ in '" + path + "'");
      pointer += "/" + segment.substr(b + 1, close - b - 1);
    }
    start = dot + 1;
  }
  return nlohmann::ordered_json::json_pointer(pointer);
}

std::string joinPath(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::string valueText(const nlohmann::ordered_json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return atmosphere::formatNumber(v.get<double>());  // shortest text that reads back
  return v.dump();
}

}  // namespace

AtmosphereEditor::AtmosphereEditor(QWidget* parent) : QWidget(parent) {
  this->fields = new QTreeWidget;
  this->fields->setColumnCount(4);
  this->fields->setHeaderLabels({"field", "value", "unit", "range"});
  this->fields->header()->setStretchLastSection(false);
  this->fields->header()->setSectionResizeMode(0, QHeaderView::Interactive);
  this->fields->header()->setSectionResizeMode(1, QHeaderView::Stretch);
  this->fields->header()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
  this->fields->header()->setSectionResizeMode(3, QHeaderView::Interactive);
  this->fields->setColumnWidth(0, 210);
  this->fields->setColumnWidth(3, 120);
  this->setMinimumWidth(520);
  this->fields->setEditTriggers(QAbstractItemView::NoEditTriggers);  // only the value column: below
  connect(this->fields, &QTreeWidget::itemDoubleClicked, this, [this](QTreeWidgetItem* item, int) {
    if (item->flags() & Qt::ItemIsEditable) this->fields->editItem(item, 1);
  });
  connect(this->fields, &QTreeWidget::itemChanged, this, [this](QTreeWidgetItem* item, int column) { this->edited(item, column); });
  // Components are added and removed from the context menu of "components" and of each one.
  this->fields->setContextMenuPolicy(Qt::CustomContextMenu);
  connect(this->fields, &QTreeWidget::customContextMenuRequested, this, [this](const QPoint& at) {
    QTreeWidgetItem* item = this->fields->itemAt(at);
    const std::string path = item ? item->data(0, kPathRole).toString().toStdString() : "";
    const std::string prefix = "components.";
    QMenu menu;
    if (path == "components") {
      menu.addAction("Add component...", this, [this] {
        const QString name = QInputDialog::getText(this, "Add component", "Name of the new component:");
        if (!name.isEmpty()) this->addComponent(name.toStdString());
      });
    } else if (path.rfind(prefix, 0) == 0 && path.find('.', prefix.size()) == std::string::npos) {
      const std::string name = path.substr(prefix.size());
      menu.addAction(qs("Remove " + name), this, [this, name] { this->removeComponent(name); });
    }
    if (!menu.isEmpty()) menu.exec(this->fields->viewport()->mapToGlobal(at));
  });
  this->status = new QLabel;
  this->status->setWordWrap(true);
  this->status->setTextInteractionFlags(Qt::TextSelectableByMouse);
  this->debounce = new QTimer(this);
  this->debounce->setSingleShot(true);
  this->debounce->setInterval(500);
  connect(this->debounce, &QTimer::timeout, this, [this] {
    if (this->changed) this->changed(this->doc);
  });
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(this->fields, 1);
  layout->addWidget(this->status);
  this->setDocument(Json(), "");
}

void AtmosphereEditor::setDebounceMs(int ms) { this->debounce->setInterval(ms); }

void AtmosphereEditor::flush() {
  if (!this->debounce->isActive()) return;
  this->debounce->stop();
  if (this->changed) this->changed(this->doc);
}

bool AtmosphereEditor::changePending() const { return this->debounce->isActive(); }

QString AtmosphereEditor::message() const { return this->status->property("rejected").toString(); }

void AtmosphereEditor::setDocument(const Json& document, const std::string& sourceName) {
  this->debounce->stop();
  this->doc = document;
  this->source = sourceName;
  this->status->setProperty("rejected", QString());
  this->status->setStyleSheet(QString());
  this->status->setText(this->hasDocument() ? "Double-click a value to edit it; the tables are recomputed when the edits pause."
                                            : "No atmosphere: choose a preset or load a JSON file.");
  this->fields->clear();
  this->rebuild();
}

void AtmosphereEditor::scheduleRebuild() {
  // Not now: the edit may come from an item or a combo box of the tree, which must outlive it.
  QTimer::singleShot(0, this, [this] { this->rebuild(); });
}

void AtmosphereEditor::rebuild() {
  std::set<std::string> expanded;
  for (QTreeWidgetItemIterator it(this->fields); *it; ++it)
    if ((*it)->isExpanded()) expanded.insert((*it)->data(0, kPathRole).toString().toStdString());
  const bool first = this->fields->topLevelItemCount() == 0;
  this->building = true;
  this->fields->clear();
  if (this->hasDocument()) addItems(this->fields->invisibleRootItem(), this->doc, "", "", "");
  for (QTreeWidgetItemIterator it(this->fields); *it; ++it) {
    const std::string path = (*it)->data(0, kPathRole).toString().toStdString();
    // At first: every component and its parts open, long arrays shut.
    const bool open = first ? (path == "components" || path.rfind("components.", 0) == 0) && std::count(path.begin(), path.end(), '.') <= 2
                            : expanded.count(path) > 0;
    (*it)->setExpanded(open);
  }
  this->building = false;
  this->describe();
}

void AtmosphereEditor::addItems(QTreeWidgetItem* parent, const Json& value, const std::string& path,
                                const std::string& where, const std::string& type) {
  for (const auto& item : value.items()) {
    const std::string key = item.key();
    const std::string childPath = value.is_array() ? path + "[" + key + "]" : joinPath(path, key);
    auto* child = new QTreeWidgetItem(parent);
    child->setText(0, qs(value.is_array() ? "[" + key + "]" : key));
    child->setData(0, kPathRole, qs(childPath));
    if (const atmosphere::Field* f = value.is_object() ? atmosphere::findField(where, type, key) : nullptr) {
      child->setText(2, f->unit);
      child->setText(3, f->range);
      const QString hint = QString(f->unit).isEmpty() ? QString(f->range) : QString("%1 in %2").arg(f->range, f->unit);
      child->setToolTip(0, hint);
      child->setToolTip(1, hint);
    }
    const Json& v = item.value();
    if (v.is_object()) {
      const std::string childWhere = atmosphere::fieldPattern(childPath);
      const std::string selector = atmosphere::selectorKey(childWhere);
      const std::string childType = !selector.empty() && v.contains(selector) && v[selector].is_string() ? v[selector].get<std::string>() : "";
      addItems(child, v, childPath, childWhere, childType);
      continue;
    }
    if (value.is_object() && !where.empty() && key == atmosphere::selectorKey(where)) {
      // A type or model: the table's choices.
      auto* choice = new QComboBox;
      for (const std::string& t : atmosphere::fieldTypes(where)) choice->addItem(qs(t));
      if (choice->findText(qs(valueText(v))) < 0) choice->addItem(qs(valueText(v)));
      choice->setCurrentText(qs(valueText(v)));
      this->fields->setItemWidget(child, 1, choice);
      connect(choice, &QComboBox::textActivated, this, [this, path](const QString& t) { this->setType(path, t.toStdString()); });
      choice->setToolTip(child->toolTip(1));
      continue;
    }
    child->setText(1, qs(valueText(v)));
    child->setFlags(child->flags() | Qt::ItemIsEditable);
  }
  if (!value.is_object()) return;
  // The optional keys the table knows and the object lacks: grey, empty, editable (a value adds them).
  const std::string selector = atmosphere::selectorKey(where);
  for (const atmosphere::Field& f : atmosphere::atmosphereFields()) {
    if (where != f.where || (*f.type != '\0' && type != f.type) || selector == f.key || value.contains(f.key)) continue;
    auto* child = new QTreeWidgetItem(parent);
    child->setText(0, f.key);
    child->setForeground(0, QBrush(Qt::gray));
    child->setData(0, kPathRole, qs(joinPath(path, f.key)));
    child->setText(2, f.unit);
    child->setText(3, f.range);
    child->setToolTip(0, QString("optional, not set (e.g. %1)").arg(f.exampleJson ? f.exampleJson : "see docs/atmosphere-format.md"));
    child->setFlags(child->flags() | Qt::ItemIsEditable);
  }
}

const atmosphere::Field* AtmosphereEditor::optionalField(const std::string& path) const {
  const std::size_t dot = path.rfind('.');
  const std::string parent = dot == std::string::npos ? "" : path.substr(0, dot);
  const std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
  const auto pointer = pointerOf(parent);
  if (!this->doc.contains(pointer) || !this->doc[pointer].is_object()) return nullptr;
  const Json& object = this->doc[pointer];
  const std::string where = atmosphere::fieldPattern(parent);
  const std::string selector = atmosphere::selectorKey(where);
  const std::string type = !selector.empty() && object.contains(selector) && object[selector].is_string() ? object[selector].get<std::string>() : "";
  return atmosphere::findField(where, type, key);
}

QTreeWidgetItem* AtmosphereEditor::itemAt(const std::string& path) const {
  for (QTreeWidgetItemIterator it(this->fields); *it; ++it)
    if ((*it)->data(0, kPathRole).toString().toStdString() == path) return *it;
  return nullptr;
}

void AtmosphereEditor::edited(QTreeWidgetItem* item, int column) {
  if (this->building || column != 1) return;
  this->setValue(item->data(0, kPathRole).toString().toStdString(), item->text(1).toStdString());
}

std::string AtmosphereEditor::setValue(const std::string& path, const std::string& text) {
  if (QTreeWidgetItem* item = this->itemAt(path); item && (item->flags() & Qt::ItemIsEditable)) {
    const bool was = this->building;
    this->building = true;
    item->setText(1, qs(text));  // as typed (kept when rejected)
    this->building = was;
  }
  std::string problem;
  Json candidate = this->doc;
  bool added = false;
  try {
    const auto pointer = pointerOf(path);
    const atmosphere::Field* optional = candidate.contains(pointer) ? nullptr : this->optionalField(path);
    added = optional != nullptr;
    if (!this->hasDocument() || path.empty() || (!candidate.contains(pointer) && !optional)) {
      problem = this->source + ": " + path + ": no such field";
    } else if (optional ? optional->exampleJson && *optional->exampleJson == '"' : candidate[pointer].is_string()) {
      candidate[pointer] = text;
    } else {
      try {
        candidate[pointer] = Json::parse(text);
      } catch (const Json::parse_error&) {
        problem = this->source + ": " + path + ": expected a number (or a JSON array or object), got '" + text + "'";
      }
    }
  } catch (const std::exception& e) {
    problem = this->source + ": " + path + ": " + e.what();
  }
  if (!problem.empty()) return this->reject(path, problem);
  const bool object = candidate[pointerOf(path)].is_object();
  problem = this->apply(path, std::move(candidate));
  // A new key, or a value that became an object (a spectrum table): items as any other's.
  if (problem.empty() && (added || object)) this->scheduleRebuild();
  return problem;
}

std::string AtmosphereEditor::setType(const std::string& objectPath, const std::string& type) {
  Json candidate = this->doc;
  try {
    const auto pointer = pointerOf(objectPath);
    candidate[pointer] = atmosphere::withFieldType(candidate.value(pointer, Json::object()), atmosphere::fieldPattern(objectPath), type);
  } catch (const std::exception& e) {
    return this->reject(objectPath, this->source + ": " + objectPath + ": " + e.what());
  }
  const std::string problem = this->apply(joinPath(objectPath, atmosphere::selectorKey(atmosphere::fieldPattern(objectPath))), std::move(candidate));
  if (problem.empty()) this->scheduleRebuild();
  return problem;
}

std::string AtmosphereEditor::addComponent(const std::string& name) {
  const std::string path = "components." + name;
  if (name.empty() || name.find_first_of(".[]/~") != std::string::npos)
    return this->reject("components", this->source + ": " + path + ": expected a name without . [ ] / ~");
  if (!this->hasDocument() || this->doc.value("components", Json::object()).contains(name))
    return this->reject("components", this->source + ": " + path + ": the component exists already");
  Json component = Json::object();
  for (const atmosphere::Field& f : atmosphere::atmosphereFields())
    if (std::string("components.*") == f.where && f.exampleJson && *f.exampleJson == '{')  // density, optics, phase
      component[f.key] = Json::parse(f.exampleJson);
  Json candidate = this->doc;
  candidate["components"][name] = component;
  const std::string problem = this->apply("components", std::move(candidate));
  if (problem.empty()) this->scheduleRebuild();
  return problem;
}

std::string AtmosphereEditor::removeComponent(const std::string& name) {
  const std::string path = "components." + name;
  if (!this->hasDocument() || !this->doc.value("components", Json::object()).contains(name))
    return this->reject("components", this->source + ": " + path + ": no such component");
  Json candidate = this->doc;
  candidate["components"].erase(name);
  const std::string problem = this->apply(path, std::move(candidate));
  if (problem.empty()) this->scheduleRebuild();
  return problem;
}

std::string AtmosphereEditor::reject(const std::string& path, const std::string& problem) {
  if (QTreeWidgetItem* item = this->itemAt(path)) {
    const bool was = this->building;
    this->building = true;
    item->setForeground(1, QBrush(Qt::red));
    item->setToolTip(1, qs(problem));
    this->building = was;
  }
  this->status->setProperty("rejected", qs(problem));
  this->status->setStyleSheet("color: #c00000");
  this->status->setText(qs(problem));
  return problem;
}

std::string AtmosphereEditor::apply(const std::string& path, Json candidate) {
  try {
    atmosphere::parseAtmosphere(candidate.dump(), this->source, atmosphere::WavelengthSet::rgb().nm);
  } catch (const std::exception& e) {
    return this->reject(path, e.what());
  }
  this->doc = std::move(candidate);
  this->status->setProperty("rejected", QString());
  this->status->setStyleSheet(QString());
  this->status->setText(qs("accepted: " + path + "; the tables are recomputed when the edits pause"));
  if (QTreeWidgetItem* item = this->itemAt(path); item && (item->flags() & Qt::ItemIsEditable)) {
    this->building = true;
    item->setForeground(1, this->palette().text());
    item->setText(1, qs(valueText(this->doc[pointerOf(path)])));  // as the document holds it
    this->building = false;
  }
  this->describe();
  this->debounce->start();
  return {};
}

void AtmosphereEditor::describe() {
  if (!this->hasDocument()) return;
  atmosphere::ParameterMap p;
  try {
    p = atmosphere::atmosphereParameters(
        atmosphere::parseAtmosphere(this->doc.dump(), this->source, atmosphere::WavelengthSet::rgb().nm));
  } catch (const std::exception&) {
    return;
  }
  // Each component's coefficients at the view's wavelengths, as Describe.hpp writes them.
  for (QTreeWidgetItemIterator it(this->fields); *it; ++it) {
    const std::string path = (*it)->data(0, kPathRole).toString().toStdString();
    if (path.rfind("components.", 0) != 0 || path.find('.', 11) != std::string::npos) continue;
    const std::string k = path.substr(11);
    const std::string key = "component." + k + ".";
    (*it)->setToolTip(0, qs("at " + p["wavelengthsNm"] + " nm: scattering " + p[key + "scatteringPerM"] +
                            " 1/m, absorption " + p[key + "absorptionPerM"] + " 1/m; phase " + p[key + "phases"]));
  }
}

void AtmosphereEditor::saveJson(const std::string& path) const {
  if (!this->hasDocument()) throw std::runtime_error(path + ": no atmosphere to save");
  output::checkWritable(path, {".json"});
  output::OutputFile out(path);
  {
    std::ofstream file(out.tempPath(), std::ios::binary);
    file << this->doc.dump(2) << "\n";
    if (!file.flush()) throw std::runtime_error(path + ": cannot write");
  }
  out.commit();
}

}  // namespace umbra::gui
