#pragma once
// The fields of an atmosphere file (docs/atmosphere-format.md) described in one table: where
// each key lives, which type/model it belongs to, its unit, its range and a default. An
// editor builds its form from this table (units and ranges as hints, the type and model
// choices, the fields a new type starts with); the values are checked by parseAtmosphere,
// which stays the only validator. Adding a key or a type to the format is one line in
// Fields.cpp (tests/atmosphere/test_fields.cpp checks the table against the parser).
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace umbra::atmosphere {

struct Field {
  /// The object the key lives in, with the component name as '*': "" (the top level),
  /// "refraction", "components.*", "components.*.density", "components.*.optics",
  /// "components.*.optics.refractiveIndex", "components.*.optics.vanDeHulst",
  /// "components.*.optics.hygroscopicGrowth", "components.*.phase".
  const char* where;
  /// The value of the object's selector ("type" or "model") the key belongs to; "" for
  /// every object at `where`. A line whose key is the selector itself declares a type.
  const char* type;
  const char* key;
  const char* unit;   ///< "" when dimensionless or not a number
  const char* range;  ///< what the parser accepts, as text ("> 0", "[-0.999999, 0.999999], spectrum")
  /// A valid value as JSON text: what a new object of this type starts with when the key
  /// is required; nullptr: no value stands alone (it needs others changed with it).
  const char* exampleJson;
  bool required = true;
  /// A key that this one replaces when it is added ("anglesDeg" replaces "cosTheta").
  const char* replaces = nullptr;
};

/// Every line of the table.
const std::vector<Field>& atmosphereFields();

/// "components.dust.optics.vanDeHulst" -> "components.*.optics.vanDeHulst"; a mixture's part,
/// "components.haze.optics.of.soot", -> "components.*.optics".
std::string fieldPattern(const std::string& objectPath);

/// The selector key of the objects at `where` ("type", "model"), "" when they have none.
std::string selectorKey(const std::string& where);
/// The types (selector values) the table knows at `where`, in table order.
std::vector<std::string> fieldTypes(const std::string& where);

/// The keys the table describes for an object at `where` whose selector value is `type`
/// ("" for none): the lines of that type and those of every type, in table order. The
/// reader (AtmosphereReader.cpp) accepts these keys and no others.
std::vector<std::string> fieldKeys(const std::string& where, const std::string& type = "");

/// The description of `key` in an object at `where` whose selector value is `type` (""
/// for none); nullptr when the table does not know it.
const Field* findField(const std::string& where, const std::string& type, const std::string& key);

/// `object` (at `where`) turned into type `type`: the selector set, the keys the new type
/// knows kept, the other keys of the old type dropped, the new type's required keys filled
/// in with their defaults. Throws std::invalid_argument for a type the table does not know.
nlohmann::ordered_json withFieldType(const nlohmann::ordered_json& object, const std::string& where,
                                     const std::string& type);

}  // namespace umbra::atmosphere
