#include "geolens/lens/lens_options.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geolens/core/errors.h"

namespace geolens {
namespace {

// Every name a face may pass parses to a value whose name is the same, the names are distinct,
// and a name that is none of them is refused naming the parser, the name and every name.
template <class Parse>
void ExpectNamesRoundTrip(Parse parse, const std::vector<std::string>& names,
                          const std::string& refusal) {
  for (const std::string& name : names) EXPECT_EQ(to_string(parse(name)), name);
  for (size_t i = 0; i < names.size(); ++i)
    for (size_t j = i + 1; j < names.size(); ++j) EXPECT_NE(parse(names[i]), parse(names[j]));
  try {
    parse("Paper ");
    FAIL() << "accepted 'Paper '";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), refusal);
  }
}

TEST(LensOptions, EveryEnumNameRoundTripsAndAnUnknownOneIsRefusedNamingTheChoices) {
  ExpectNamesRoundTrip(parse_flatten_weights, {"paper", "cotan"},
                       "parse_flatten_weights: unknown weights 'Paper ' (expected paper or cotan)");
  ExpectNamesRoundTrip(parse_metric, {"paper", "spectrum"},
                       "parse_metric: unknown metric 'Paper ' (expected paper or spectrum)");
  ExpectNamesRoundTrip(
      parse_boundary, {"sliding", "fixed", "free"},
      "parse_boundary: unknown boundary 'Paper ' (expected sliding, fixed or free)");
  ExpectNamesRoundTrip(
      parse_texture_weights, {"cotan", "cotan+", "mvc"},
      "parse_texture_weights: unknown texture weights 'Paper ' (expected cotan, cotan+ or mvc)");
  ExpectNamesRoundTrip(parse_extent, {"global", "local"},
                       "parse_extent: unknown extent 'Paper ' (expected global or local)");
  ExpectNamesRoundTrip(
      parse_lens_model, {"focus", "lift", "field", "auto"},
      "parse_lens_model: unknown lens model 'Paper ' (expected focus, lift, field or auto)");
}

}  // namespace
}  // namespace geolens

namespace geolens {
namespace {

// The table every face binds: each field reads its default back from LensOptions{}, sets only its
// own member (a value other than the default, set from text, reads back and changes no other
// field), refuses text that does not read naming itself, and the names are distinct and the ones
// InvalidOption and unread_options use.
TEST(LensOptionFields, EachFieldSetsItsOwnMemberFromTextAndReadsItBack) {
  const LensOptions defaults;
  const std::vector<LensOptionField>& fields = lens_option_fields();
  ASSERT_EQ(fields.size(), 15u);
  for (const LensOptionField& field : fields) {
    SCOPED_TRACE(field.name);
    EXPECT_FALSE(field.help.empty());
    EXPECT_EQ(&lens_option_field(field.name), &field);
    // Another value than the default: the next choice, or the default plus 3.
    std::string other;
    if (field.type == LensOptionField::Type::kChoice) {
      ASSERT_GE(field.choices.size(), 2u);
      other = field.choices[0] == field.get(defaults) ? field.choices[1] : field.choices[0];
    } else {
      other = field.type == LensOptionField::Type::kInteger
                  ? std::to_string(std::stoi(field.get(defaults)) + 3)
                  : number_text(std::stod(field.get(defaults)) + 3);
    }
    LensOptions set = defaults;
    field.set(set, other);
    EXPECT_EQ(field.get(set), other);
    for (const LensOptionField& rest : fields)
      if (&rest != &field) EXPECT_EQ(rest.get(set), rest.get(defaults)) << rest.name;
    field.set(set, field.get(defaults));
    for (const LensOptionField& any : fields) EXPECT_EQ(any.get(set), any.get(defaults));
    try {
      field.set(set, "2.5x");
      FAIL() << "accepted '2.5x'";
    } catch (const InvalidOption& e) {
      EXPECT_EQ(e.option, field.name);
      EXPECT_NE(e.problem.find("'2.5x'"), std::string::npos) << e.problem;
    }
  }
  EXPECT_EQ(lens_option_field("mesh").get(defaults), "100");
  EXPECT_EQ(lens_option_field("tolerance").get(defaults), "0.001");
  EXPECT_EQ(lens_option_field("model").get(defaults), "focus");
  EXPECT_THROW(lens_option_field("meshes"), InvalidInput);
  // Every option unread_options may name, but the lens's own profile and footprint.
  for (const char* name : {"mesh_tolerance", "subdivide", "extent", "extent_factor", "texture",
                           "weights", "metric", "alpha", "boundary"})
    EXPECT_NO_THROW(lens_option_field(name)) << name;
}

TEST(LensOptionFields, AChoiceTakesItsNamesOnlyAndAnIntegerNoFraction) {
  LensOptions o;
  lens_option_field("model").set(o, "lift");
  EXPECT_EQ(o.model, LensModel::kLift);
  lens_option_field("subdivide").set(o, "2");
  EXPECT_EQ(o.subdivision.max_levels, 2);
  lens_option_field("alpha").set(o, "0.25");
  EXPECT_EQ(o.flatten.alpha, 0.25);
  try {
    lens_option_field("model").set(o, "bulge");
    FAIL();
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.problem, "must be focus, lift, field or auto, got 'bulge'");
  }
  try {
    lens_option_field("mesh").set(o, "1e3");
    FAIL();
  } catch (const InvalidOption& e) {
    EXPECT_EQ(e.problem, "must be an integer, got '1e3'");
  }
  EXPECT_EQ(option_flag("mesh_tolerance"), "--mesh-tolerance");
}

}  // namespace
}  // namespace geolens
