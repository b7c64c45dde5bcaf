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
