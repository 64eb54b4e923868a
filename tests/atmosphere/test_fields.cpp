// The field table (atmosphere/Fields.hpp) against the reader it describes
// (parseAtmosphere), which takes the keys it accepts from it: every type the reader accepts
// has lines, every line's example value is accepted, every key of the shipped presets is
// described, a type switch keeps what the new type shares with the old one, and
// docs/atmosphere-format.md lists the same keys and types.
#include "Atmosphere.hpp"
#include "Fields.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <string>

using namespace umbra::atmosphere;
using json = nlohmann::ordered_json;

namespace {

const std::vector<double> kRgb{680.0, 550.0, 440.0};

/// A small valid atmosphere with one component (coefficients, isotropic phase).
json baseDocument() {
  return json::parse(R"({"bottomRadiusM": 6371000, "topRadiusM": 6471000,
    "components": {"molecules": {"density": {"type": "exponential", "scaleHeightM": 8000},
                         "optics": {"model": "coefficients", "scatteringPerM": 4e-6},
                         "phase": {"type": "isotropic"}}}})");
}

/// The object at `where` ("components.*.optics.vanDeHulst", '*' the one component), made
/// as the table says where it is missing: each parent of the type the key belongs to, the
/// object itself from its line's example value.
json& at(json& doc, const std::string& where) {
  if (where.empty()) return doc;
  const std::size_t dot = where.rfind('.');
  const std::string parentWhere = dot == std::string::npos ? "" : where.substr(0, dot);
  std::string key = dot == std::string::npos ? where : where.substr(dot + 1);
  json& parent = at(doc, parentWhere);
  if (key == "*") key = "molecules";
  for (const Field& f : atmosphereFields()) {
    if (parentWhere != f.where || key != f.key) continue;
    if (*f.type != '\0' && parent[selectorKey(parentWhere)] != f.type) parent = withFieldType(parent, parentWhere, f.type);
    if (!parent.contains(key)) parent[key] = json::parse(f.exampleJson);
  }
  return parent[key];
}

std::string errorOf(const json& doc) {
  try {
    parseAtmosphere(doc.dump(), "t.json", kRgb);
  } catch (const AtmosphereError& e) {
    return e.what();
  }
  return {};
}

/// The list the reader gives in "expected one of: a, b, c, got ..." for an unknown type.
std::set<std::string> readerTypes(const std::string& where) {
  json doc = baseDocument();
  at(doc, where) = json{{selectorKey(where), "no-such-type"}};
  const std::string message = errorOf(doc);
  std::smatch m;
  EXPECT_TRUE(std::regex_search(message, m, std::regex("expected one of: (.*), got \"no-such-type\""))) << message;
  std::set<std::string> types;
  const std::string list = m[1];
  const std::regex comma(", ");
  for (std::sregex_token_iterator i(list.begin(), list.end(), comma, -1), end; i != end; ++i) types.insert(*i);
  return types;
}

void expectDescribed(const json& object, const std::string& path, const std::string& preset) {
  const std::string where = fieldPattern(path);
  const std::string selector = selectorKey(where);
  const std::string type = !selector.empty() && object.contains(selector) ? object[selector].get<std::string>() : "";
  for (const auto& item : object.items()) {
    const std::string child = path.empty() ? item.key() : path + "." + item.key();
    const bool named = path == "components" ||  // component names and a mixture's parts' are the user's
                       (path.size() > 10 && path.compare(path.size() - 10, 10, ".optics.of") == 0);
    if (named) {
      expectDescribed(item.value(), child, preset);
      continue;
    }
    EXPECT_NE(findField(where, type, item.key()), nullptr) << preset << ": " << child << " has no line in the field table";
    const bool spectrum = item.value().is_object() && item.value().contains("wavelengthsNm") && item.value().contains("values") &&
                          !item.value().contains("type");
    if (item.value().is_object() && !spectrum) expectDescribed(item.value(), child, preset);
  }
}

}  // namespace

TEST(Fields, EveryTypeTheReaderKnowsHasLines) {
  for (const std::string where : {"components.*.density", "components.*.optics", "components.*.phase"}) {
    const std::vector<std::string> table = fieldTypes(where);
    EXPECT_EQ(readerTypes(where), std::set<std::string>(table.begin(), table.end())) << where;
  }
}

TEST(Fields, EachTypeWithItsRequiredFieldsIsAccepted) {
  for (const std::string where : {"components.*.density", "components.*.optics", "components.*.phase"}) {
    for (const std::string& type : fieldTypes(where)) {
      json doc = baseDocument();
      json& object = at(doc, where);
      object = withFieldType(object, where, type);
      EXPECT_EQ(errorOf(doc), "") << where << " " << type << ": " << object.dump();
    }
  }
}

TEST(Fields, EachOptionalExampleIsAccepted) {
  int tried = 0;
  for (const Field& f : atmosphereFields()) {
    if (f.required || f.exampleJson == nullptr) continue;
    json doc = baseDocument();
    const std::string where = f.where;
    json& object = at(doc, where);
    if (*f.type != '\0') object = withFieldType(object, where, f.type);
    if (f.replaces) object.erase(f.replaces);
    object[f.key] = json::parse(f.exampleJson);
    EXPECT_EQ(errorOf(doc), "") << where << "." << f.key << " = " << f.exampleJson;
    ++tried;
  }
  EXPECT_GE(tried, 12);
}

TEST(Fields, EveryKeyOfThePresetsIsDescribed) {
  for (const std::string& preset : presetNames()) expectDescribed(json::parse(resolvedAtmosphereJson(preset)), "", preset);
}

TEST(Fields, ATypeSwitchKeepsWhatBothTypesShare) {
  const json hg = json::parse(R"({"type": "henyey-greenstein", "g": 0.7})");
  const json cs = withFieldType(hg, "components.*.phase", "cornette-shanks");
  EXPECT_EQ(cs, json::parse(R"({"type": "cornette-shanks", "g": 0.7})"));
  const json dhg = withFieldType(hg, "components.*.phase", "double-henyey-greenstein");
  EXPECT_EQ(dhg, json::parse(R"({"type": "double-henyey-greenstein", "g1": 0.8, "g2": -0.2, "alpha": 0.9})"));
  EXPECT_THROW(withFieldType(hg, "components.*.phase", "mie-of-mars"), std::invalid_argument);
  EXPECT_EQ(fieldPattern("components.dust.optics.vanDeHulst"), "components.*.optics.vanDeHulst");
  EXPECT_EQ(fieldPattern("components.dust"), "components.*");
  EXPECT_EQ(selectorKey("components.*.optics"), "model");
  EXPECT_EQ(selectorKey("refraction"), "");
}

TEST(Fields, ResolvedPresetIsTheMergedDocument) {
  // earth-2015-calbuco extends earth: its resolved text has no "extends", earth's ozone
  // and its own stratospheric density scale, and it loads as the same atmosphere.
  const json doc = json::parse(resolvedAtmosphereJson("earth-2015-calbuco"));
  EXPECT_FALSE(doc.contains("extends"));
  EXPECT_TRUE(doc["components"].contains("ozone"));
  EXPECT_EQ(doc["components"]["stratosphere"]["densityScale"].get<double>(), 3.0);
  const Atmosphere a = parseAtmosphere(doc.dump(), "x.json", kRgb), b = loadAtmosphere("earth-2015-calbuco", kRgb);
  EXPECT_EQ(a.components.size(), b.components.size());
  EXPECT_EQ(a.component("stratosphere").scatteringPerM, b.component("stratosphere").scatteringPerM);
  EXPECT_THROW(resolvedAtmosphereJson("venus"), AtmosphereError);
}

namespace {

// The rows of the first markdown table after the heading `heading` in
// docs/atmosphere-format.md: each row's cells, trimmed.
std::vector<std::vector<std::string>> docsTable(const std::string& heading) {
  std::ifstream in(UMBRA_SOURCE_DIR "/docs/atmosphere-format.md");
  std::string line;
  bool after = false;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    if (line == heading) after = true;
    if (!after) continue;
    if (line.rfind("|", 0) != 0) {
      if (!rows.empty()) break;
      continue;
    }
    if (line.rfind("|---", 0) == 0) continue;
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '|' && line[i - 1] != '\\') {
        const std::size_t first = cell.find_first_not_of(' ');
        cells.push_back(first == std::string::npos ? std::string() : cell.substr(first, cell.find_last_not_of(' ') - first + 1));
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    rows.push_back(cells);
  }
  EXPECT_FALSE(rows.empty()) << "no table after '" << heading << "'";
  if (!rows.empty()) rows.erase(rows.begin());  // the header
  return rows;
}

// The words in backticks of a cell.
std::set<std::string> quoted(const std::string& cell) {
  std::set<std::string> words;
  const std::regex word("`([^`]+)`");
  for (std::sregex_iterator i(cell.begin(), cell.end(), word), end; i != end; ++i) words.insert((*i)[1]);
  return words;
}

// "`name`" -> "name".
std::string unquoted(const std::string& cell) { return cell.size() > 2 ? cell.substr(1, cell.size() - 2) : cell; }

}  // namespace

// docs/atmosphere-format.md's reference tables against the field table: the keys of the top
// level and of a component, the types of densities, optics and phase functions, and each
// type's keys: the same sets, no more and no fewer.
TEST(Fields, TheFormatDocumentListsTheTablesKeysAndTypes) {
  const auto keysOf = [](const std::vector<std::vector<std::string>>& rows) {
    std::set<std::string> keys;
    for (const auto& r : rows)
      if (unquoted(r[0]) != "extends") keys.insert(unquoted(r[0]));  // resolved before the fields are read
    return keys;
  };
  const auto asSet = [](const std::vector<std::string>& v) { return std::set<std::string>(v.begin(), v.end()); };
  EXPECT_EQ(keysOf(docsTable("## Top level")), asSet(fieldKeys("")));
  EXPECT_EQ(keysOf(docsTable("## Components")), asSet(fieldKeys("components.*")));
  for (const auto& [heading, where] : std::vector<std::pair<std::string, std::string>>{
           {"### Density profiles (`density`)", "components.*.density"},
           {"### Optics (`optics`)", "components.*.optics"},
           {"### Phase functions (`phase`)", "components.*.phase"}}) {
    const auto rows = docsTable(heading);
    std::set<std::string> types;
    for (const auto& r : rows) types.insert(unquoted(r[0]));
    EXPECT_EQ(types, asSet(fieldTypes(where))) << heading;
    const std::string selector = selectorKey(where);
    for (const auto& r : rows) {
      const std::string type = unquoted(r[0]);
      // Every key of the type is in its "keys" cell (all but the selector and the free text).
      const std::set<std::string> listed = quoted(r[1]);
      for (const std::string& key : fieldKeys(where, type)) {
        if (key != selector && key != "description") {
          EXPECT_TRUE(listed.count(key)) << heading << " " << type << ": " << key << " is not in the document";
        }
      }
      // And every word quoted there is a key of the type or of an object inside it.
      for (const std::string& word : listed) {
        bool known = findField(where, type, word) != nullptr;
        for (const Field& f : atmosphereFields())
          known = known || (std::string(f.where).rfind(where + ".", 0) == 0 && word == f.key);
        EXPECT_TRUE(known || word == "mie" || word == "rayleigh") << heading << " " << type << ": `" << word
                                                                  << "` is not in the field table";
      }
    }
  }
}
