// The suite's false-alarm budget (support/significance.hpp) holds only while the number of
// comparison families, the test cases tagged [statistical] here, stays within it.

#include <catch2/catch.hpp>
#include <string>

#include "../support/significance.hpp"

TEST_CASE("statistical comparisons: the families fit the suite's false-alarm budget", "[render]") {
  int families = 0;
  for (const Catch::TestCase& test :
       Catch::getAllTestCasesSorted(*Catch::getCurrentContext().getConfig()))
    for (const std::string& tag : test.getTestCaseInfo().lcaseTags)
      if (tag == "statistical") ++families;
  INFO(families << " test cases tagged [statistical], budget " << glint_test::kComparisonFamilies);
  CHECK(families > 0);
  CHECK(families <= glint_test::kComparisonFamilies);
}
