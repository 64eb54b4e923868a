// parameterHash and the `umbra inspect` summary.

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "TestSupport.h"
#include "umbra/tables/Summary.h"

namespace umbra::tables::test {
namespace {

// An independent FNV-1a 64 (byte loop over one string), for comparison.
std::string referenceFnv1a(const std::string& bytes) {
  uint64_t h = 14695981039346656037ULL;
  for (size_t i = 0; i < bytes.size(); ++i) {
    h = (h ^ static_cast<uint8_t>(bytes[i])) * 1099511628211ULL;
  }
  static const char* digits = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) out[static_cast<size_t>(i)] = digits[h & 15];
  return out;
}

TEST(ParameterHash, KnownValues) {
  // Values computed by hand with Python (FNV-1a 64 of the "key=value\n" lines).
  EXPECT_EQ(parameterHash({}), "cbf29ce484222325");  // the FNV offset basis
  EXPECT_EQ(parameterHash({{"a", "1"}}), "ed9ed282c45f76f4");
  EXPECT_EQ(parameterHash({{"a", ""}}), "e650bb190491e58b");
  EXPECT_EQ(parameterHash({{"size", "256"}, {"kind", "shadow"}}), "fa33b0671b3869a1");
  EXPECT_EQ(referenceFnv1a("foobar"), "85944171f73967e8");  // published FNV-1a test vector

  const std::map<std::string, std::string> p = {
      {"wavelengths", "440,550,680"}, {"radius", "6.371e6"}, {"Zeta", "é"}, {"order", "4"}};
  EXPECT_EQ(parameterHash(p),
            referenceFnv1a("Zeta=é\norder=4\nradius=6.371e6\nwavelengths=440,550,680\n"));
}

TEST(ParameterHash, IsSixteenLowercaseHexDigits) {
  for (const auto& p : std::vector<std::map<std::string, std::string>>{
           {}, {{"x", "y"}}, {{"kind", "limb"}, {"n", "64"}}}) {
    const std::string h = parameterHash(p);
    ASSERT_EQ(h.size(), 16u);
    for (char ch : h) EXPECT_TRUE((ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f')) << h;
  }
}

TEST(ParameterHash, DoesNotDependOnInsertionOrder) {
  std::vector<std::pair<std::string, std::string>> entries = {
      {"b", "2"}, {"a", "1"}, {"c", "3"}, {"aa", "4"}};
  std::map<std::string, std::string> forward(entries.begin(), entries.end());
  std::map<std::string, std::string> backward(entries.rbegin(), entries.rend());
  std::map<std::string, std::string> oneByOne;
  oneByOne["c"] = "3";
  oneByOne["aa"] = "4";
  oneByOne["a"] = "1";
  oneByOne["b"] = "2";
  EXPECT_EQ(parameterHash(forward), parameterHash(backward));
  EXPECT_EQ(parameterHash(forward), parameterHash(oneByOne));
}

TEST(ParameterHash, ChangesWithAnyChange) {
  const std::map<std::string, std::string> base = {
      {"kind", "shadow"}, {"size", "256"}, {"radius", "6371000"}};
  std::vector<std::map<std::string, std::string>> variants;
  for (const auto& [key, value] : base) {
    auto v = base;
    v[key] = value + "0";  // longer value
    variants.push_back(v);
    v = base;
    v[key] = value.substr(0, value.size() - 1);  // shorter value
    variants.push_back(v);
    v = base;
    v[key][0] = static_cast<char>(v[key][0] ^ 1);  // one bit flipped
    variants.push_back(v);
    v = base;
    v.erase(key);  // entry removed
    variants.push_back(v);
    v = base;
    v.erase(key);
    v[key + "_"] = value;  // key renamed
    variants.push_back(v);
  }
  auto added = base;
  added["extra"] = "";
  variants.push_back(added);
  // Moving the boundary between key and value.
  variants.push_back({{"kind", "shadow"}, {"size2", "56"}, {"radius", "6371000"}});

  std::set<std::string> hashes = {parameterHash(base)};
  for (const auto& v : variants) {
    EXPECT_TRUE(hashes.insert(parameterHash(v)).second) << "collision for variant";
  }
}

Table handMadeTable() {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  Table t;
  t.width = 3;
  t.height = 2;
  t.channels = {"A", "B", "C"};
  // Per pixel: A, B, C.
  t.data = {1.0f, -inf, 0.5f,   //
            2.0f, nan, -1.5f,   //
            3.0f, nan, 2.0f,    //
            nan, nan, 8.0f,     //
            4.0f, nan, -3.0f,   //
            inf, inf, 0.0f};
  t.parameters = {{"kind", "test"}, {"size", "3x2"}};
  return t;
}

TEST(Summary, ExactStatisticsOverFiniteValues) {
  const TableSummary s = summarize(handMadeTable(), "dir/t.exr");
  EXPECT_EQ(s.path, "dir/t.exr");
  EXPECT_EQ(s.width, 3);
  EXPECT_EQ(s.height, 2);
  EXPECT_EQ(s.parameters, handMadeTable().parameters);
  ASSERT_EQ(s.channels.size(), 3u);

  EXPECT_EQ(s.channels[0].name, "A");
  EXPECT_EQ(s.channels[0].min, 1.0);
  EXPECT_EQ(s.channels[0].max, 4.0);
  EXPECT_EQ(s.channels[0].mean, 2.5);
  EXPECT_EQ(s.channels[0].nonFinite, 2);

  EXPECT_EQ(s.channels[1].name, "B");
  EXPECT_TRUE(std::isnan(s.channels[1].min));
  EXPECT_TRUE(std::isnan(s.channels[1].max));
  EXPECT_TRUE(std::isnan(s.channels[1].mean));
  EXPECT_EQ(s.channels[1].nonFinite, 6);

  EXPECT_EQ(s.channels[2].name, "C");
  EXPECT_EQ(s.channels[2].min, -3.0);
  EXPECT_EQ(s.channels[2].max, 8.0);
  EXPECT_EQ(s.channels[2].mean, 1.0);
  EXPECT_EQ(s.channels[2].nonFinite, 0);
}

TEST(Summary, JsonHasTheDocumentedShapeWithNullForNaN) {
  const nlohmann::json j = toJson(summarize(handMadeTable(), "dir/t.exr"));
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "path": "dir/t.exr", "width": 3, "height": 2,
    "channels": [
      {"name": "A", "min": 1.0, "max": 4.0, "mean": 2.5, "nonFinite": 2},
      {"name": "B", "min": null, "max": null, "mean": null, "nonFinite": 6},
      {"name": "C", "min": -3.0, "max": 8.0, "mean": 1.0, "nonFinite": 0}
    ],
    "parameters": {"kind": "test", "size": "3x2"}
  })");
  EXPECT_EQ(j, expected) << j.dump(2);
  EXPECT_EQ(j.dump().find("NaN"), std::string::npos);
  EXPECT_TRUE(j["channels"][1]["min"].is_null());
}

TEST(Summary, TextNamesSizeChannelsAndParameters) {
  const std::string text = formatText(summarize(handMadeTable(), "dir/t.exr"));
  EXPECT_EQ(text.rfind("dir/t.exr\n", 0), 0u) << text;
  for (const char* expected :
       {"3 x 2, 3 channels", "A: min 1  max 4  mean 2.5  non-finite 2",
        "B: no finite values  non-finite 6", "C: min -3  max 8  mean 1  non-finite 0",
        "kind = test", "size = 3x2"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                      << text;
  }
}

TEST(Summary, RejectsAnInvalidTable) {
  Table t = handMadeTable();
  t.data.pop_back();
  EXPECT_THROW(summarize(t, "x.exr"), TableError);
}

}  // namespace
}  // namespace umbra::tables::test
