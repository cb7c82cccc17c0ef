// Unit tests of the case-file key declarations (KeyTable in params.hpp): validation against a table, defaults
// computed when the object is read, the registry and the generated reference.
#include <lagfsi/error.hpp>
#include <lagfsi/params.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace lagfsi;

namespace {

const KeyTable kWidgetKeys("/widgets/* (type test)", "A widget of the tests.",
                           {{"size", nullptr, "Size (m)."},
                            {"colour", "red", "red or blue."},
                            {"count", 3, "How many."},
                            {"band", 0.0, "Band (m); default: twice the size.", kDerived}});

/// The InputError that validating `object` against the widget table throws ("" when none).
std::string error_of(const Json& object, const Json& runtime = Json::object()) {
  Params p(Json{{"w", object}}, "case.json");
  try {
    p.at("w").validate(kWidgetKeys, runtime);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(KeyTable, AnUnknownKeyIsAnErrorListingTheDeclaredKeys) {
  EXPECT_EQ(error_of({{"size", 1.0}, {"colour_", "red"}}),
            "case.json: /w/colour_: unknown key (valid keys: band, colour, count, size)");
}

TEST(KeyTable, AMissingRequiredKeyIsAnError) {
  EXPECT_EQ(error_of({{"colour", "blue"}}), "case.json: /w/size: required key is missing");
}

TEST(KeyTable, AValueOfAnotherJsonTypeThanTheDefaultIsAnError) {
  EXPECT_EQ(error_of({{"size", 1.0}, {"count", "three"}}), "case.json: /w/count: expected a number, found a string");
}

TEST(KeyTable, MissingKeysTakeTheDeclaredDefaults) {
  Params p(Json{{"size", 2.0}}, "case.json");
  p.validate(kWidgetKeys);
  EXPECT_EQ(p.json(), (Json{{"size", 2.0}, {"colour", "red"}, {"count", 3}, {"band", 0.0}}));
}

TEST(KeyTable, ValidatingLikeTheDefaultsObjectGivesTheSameResult) {
  Params a(Json{{"size", 2.0}, {"count", 5}}, "case.json"), b = Params(a.json(), "case.json");
  a.validate(kWidgetKeys);
  b.validate(kWidgetKeys.defaults());
  EXPECT_EQ(a.json(), b.json());
}

TEST(KeyTable, ARuntimeDefaultReplacesTheDeclaredOneAndAGivenValueWins) {
  Params p(Json{{"size", 2.0}}, "case.json");
  p.validate(kWidgetKeys, {{"band", 4.0}});
  EXPECT_EQ(p.json().at("band"), 4.0);
  Params q(Json{{"size", 2.0}, {"band", 1.0}}, "case.json");
  q.validate(kWidgetKeys, {{"band", 4.0}});
  EXPECT_EQ(q.json().at("band"), 1.0);
}

TEST(KeyTable, ARuntimeDefaultForAnUndeclaredKeyIsAProgramError) {
  Params p(Json{{"size", 2.0}}, "case.json");
  EXPECT_THROW(p.validate(kWidgetKeys, {{"width", 1.0}}), std::logic_error);
}

TEST(KeyTable, ATableAtNamespaceScopeIsRegistered) {
  const auto tables = key_tables();
  EXPECT_NE(std::find(tables.begin(), tables.end(), &kWidgetKeys), tables.end());
}

TEST(KeyTable, TheReferenceHasASectionPerTableWithRequiredAndDerivedDefaultsNamed) {
  const std::string md = key_reference_markdown();
  EXPECT_NE(md.find("## /widgets/* (type test)\n\nA widget of the tests.\n"), std::string::npos);
  EXPECT_NE(md.find("| `size` | required | Size (m). |"), std::string::npos);
  EXPECT_NE(md.find("| `colour` | `\"red\"` | red or blue. |"), std::string::npos);
  EXPECT_NE(md.find("| `band` | derived (see description) | Band (m); default: twice the size. |"), std::string::npos);
}

TEST(KeyTable, ALocalTableLeavesTheRegistryWhenDestroyed) {
  const size_t before = key_tables().size();
  {
    const KeyTable local("/local", "A table of this test.", {{"a", 1, "A."}});
    EXPECT_EQ(key_tables().size(), before + 1);
  }
  EXPECT_EQ(key_tables().size(), before);
}
