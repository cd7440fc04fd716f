// The text of a float (detail/text.hpp: write_number, format_number, append_number): it reads
// back with std::strtof as the same float, bit for bit; it is the shortest that does, checked
// against std::to_chars's shortest form and, independently, by trying the nearest texts with
// one significant digit fewer; and its notation is the one asked for.

#include <bit>
#include <catch2/catch.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "glint/detail/text.hpp"
#include "glint/math/random.hpp"

namespace {

using glint::detail::FloatNotation;

std::uint32_t float_bits(float v) {
  return std::bit_cast<std::uint32_t>(v);
}

/// What std::strtof, the C library's reader and independent of std::to_chars, makes of `text`;
/// NaN when it does not take the whole text.
float read_with_strtof(const std::string& text) {
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);
  return end == text.c_str() + text.size() ? v : std::numeric_limits<float>::quiet_NaN();
}

std::string to_chars_shortest(float v) {
  char text[64];
  return std::string(text, std::to_chars(text, text + sizeof text, v).ptr);
}

/// The significant digits of a decimal text, leading and trailing zeros dropped ("0.00120" and
/// "1.2e-03" both give "12", "100000" gives "1").
std::string significant_digits(const std::string& text) {
  std::string digits;
  for (const char c : text.substr(0, text.find('e')))
    if (c >= '0' && c <= '9') digits += c;
  const std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) return "";
  return digits.substr(first, digits.find_last_not_of('0') - first + 1);
}

/// True when some decimal of `count` significant digits reads back as `v` (finite, not 0).
/// The ones that read back as v form an interval around v, so it is enough to try the nearest
/// such decimal below |v| and the nearest above: v's exact digits (a float converts to double
/// exactly, and printf prints a double's exact expansion to 70 digits, more than any float
/// has), cut to `count` digits, then that plus one in its last digit.
bool fewer_digits_read_back(float v, int count) {
  char exact[96];
  std::snprintf(exact, sizeof exact, "%.70e", std::fabs(double(v)));
  const std::string text = exact;
  const std::string all = text.substr(0, 1) + text.substr(2, text.find('e') - 2);
  const int exponent = std::atoi(text.c_str() + text.find('e') + 1);
  std::string below = all.substr(0, std::size_t(count));
  std::string above = below;
  int at = count - 1;
  while (at >= 0 && above[std::size_t(at)] == '9')
    above[std::size_t(at--)] = '0';
  int above_exponent = exponent;
  if (at >= 0)
    ++above[std::size_t(at)];
  else
    above = "1" + above.substr(0, above.size() - 1), ++above_exponent;
  const auto reads_back = [&](const std::string& digits, int e) {
    const std::string candidate =
        (v < 0 ? "-" : "") + digits.substr(0, 1) + "." + digits.substr(1) + "e" + std::to_string(e);
    return float_bits(read_with_strtof(candidate)) == float_bits(v);
  };
  return reads_back(below, exponent) || reads_back(above, above_exponent);
}

/// Every property of the text of `v` in `notation`, for a finite v.
void check_text(float v, FloatNotation notation) {
  const std::string text = glint::detail::format_number(v, notation);
  const std::string reference = to_chars_shortest(v);
  INFO("value " << reference << ", text '" << text << "'");
  REQUIRE(text.size() <= glint::detail::kMaxFloatTextLength);
  REQUIRE(float_bits(read_with_strtof(text)) == float_bits(v));
  // Shortest counts characters: a whole number in plain notation has all its digits, as many as
  // its magnitude takes (2147483648 is shorter than 2.1474836e+09), and no fewer digits would
  // do. Any other text has the fewest significant digits.
  const bool whole_number = text.find_first_of(".e") == std::string::npos;
  if (!whole_number) {
    REQUIRE(significant_digits(text) == significant_digits(reference));
    const int digits = int(significant_digits(text).size());
    if (digits > 1) REQUIRE_FALSE(fewer_digits_read_back(v, digits - 1));
  }
  if (notation == FloatNotation::shortest) {
    REQUIRE(text == reference);
  } else {
    char plain[64];
    const std::string plain_text(
        plain, std::to_chars(plain, plain + sizeof plain, v, std::chars_format::fixed).ptr);
    REQUIRE(text == (plain_text.size() <= reference.size() + 3 ? plain_text : reference));
  }
  std::string appended = "x=";
  glint::detail::append_number(appended, v, notation);
  REQUIRE(appended == "x=" + text);
}

constexpr float kMax = std::numeric_limits<float>::max();
constexpr float kMinNormal = std::numeric_limits<float>::min();
constexpr float kMinSubnormal = std::numeric_limits<float>::denorm_min();

}  // namespace

TEST_CASE("float text: known values", "[detail][text]") {
  using glint::detail::format_number;
  CHECK(format_number(0.1f) == "0.1");
  CHECK(format_number(-0.0f) == "-0");
  CHECK(format_number(0.0f) == "0");
  CHECK(format_number(1e-7f) == "1e-07");
  CHECK(format_number(100000.0f) == "1e+05");
  CHECK(format_number(123456.0f) == "123456");
  CHECK(format_number(16777217.0f) == "16777216");  // 2^24 + 1 is no float
  CHECK(format_number(kMax) == "3.4028235e+38");
  CHECK(format_number(kMinSubnormal) == "1e-45");
  CHECK(format_number(1.0f / 3.0f) == "0.33333334");
  CHECK(format_number(std::numeric_limits<float>::infinity()) == "inf");
  CHECK(format_number(-std::numeric_limits<float>::infinity()) == "-inf");
  CHECK(format_number(std::numeric_limits<float>::quiet_NaN()) == "nan");

  const FloatNotation plain = FloatNotation::plain_unless_long;
  CHECK(format_number(100000.0f, plain) == "100000");
  CHECK(format_number(1e-5f, plain) == "0.00001");
  CHECK(format_number(1e-7f, plain) == "1e-07");  // 0.0000001 is 4 characters longer
  CHECK(format_number(1e30f, plain) == "1e+30");  // plain notation would take 31 digits
  CHECK(format_number(-0.0f, plain) == "-0");
  CHECK(format_number(kMinSubnormal, plain) == "1e-45");
  CHECK(format_number(0.1f, plain) == "0.1");
}

TEST_CASE("float text: edge values read back with strtof in the fewest digits", "[detail][text]") {
  const std::vector<float> values = {0.0f,
                                     -0.0f,
                                     kMinSubnormal,
                                     -kMinSubnormal,
                                     2.0f * kMinSubnormal,
                                     std::nextafter(kMinNormal, 0.0f),  // the largest subnormal
                                     kMinNormal,
                                     -kMinNormal,
                                     std::nextafter(kMinNormal, 1.0f),
                                     kMax,
                                     -kMax,
                                     std::nextafter(kMax, 0.0f),
                                     std::numeric_limits<float>::epsilon(),
                                     0.1f,
                                     0.2f,
                                     0.3f,
                                     -0.1f,
                                     1e-7f,
                                     1e-5f,
                                     1e7f,
                                     1e10f,
                                     1e30f,
                                     1.0f,
                                     -1.0f,
                                     2.0f,
                                     3.0f,
                                     10.0f,
                                     99960.0f,
                                     100000.0f,
                                     123456.0f,
                                     16777216.0f,
                                     16777218.0f,
                                     2147483648.0f,
                                     std::nextafter(1.0f, 2.0f),
                                     std::nextafter(1.0f, 0.0f),
                                     1.0f / 3.0f,
                                     3.14159265f,
                                     0.30000001f,
                                     123456.789f};
  for (const FloatNotation notation : {FloatNotation::shortest, FloatNotation::plain_unless_long})
    for (const float v : values)
      check_text(v, notation);
}

TEST_CASE("float text: every exponent, from random bit patterns", "[detail][text]") {
  glint::Pcg32 rng(2024, 11);
  int tested = 0;
  for (int i = 0; i < 20000; ++i) {
    const float v = std::bit_cast<float>(rng.next_u32());
    if (!std::isfinite(v)) continue;
    check_text(v, FloatNotation::shortest);
    check_text(v, FloatNotation::plain_unless_long);
    ++tested;
  }
  CHECK(tested > 19000);
}

TEST_CASE("float text: infinities and NaNs read back with strtof", "[detail][text]") {
  const float inf = std::numeric_limits<float>::infinity();
  for (const FloatNotation notation : {FloatNotation::shortest, FloatNotation::plain_unless_long}) {
    CHECK(read_with_strtof(glint::detail::format_number(inf, notation)) == inf);
    CHECK(read_with_strtof(glint::detail::format_number(-inf, notation)) == -inf);
    CHECK(std::isnan(read_with_strtof(
        glint::detail::format_number(std::numeric_limits<float>::quiet_NaN(), notation))));
  }
}

TEST_CASE("float text: the longest text fits the bound exactly", "[detail][text]") {
  char text[glint::detail::kMaxFloatTextLength];
  // Plain notation would be the longest, but it is not chosen for the smallest subnormal; to
  // see that the bound holds it, ask std::to_chars directly.
  const auto plain =
      std::to_chars(text, text + sizeof text, -kMinSubnormal, std::chars_format::fixed);
  REQUIRE(plain.ec == std::errc{});
  CHECK(std::size_t(plain.ptr - text) == glint::detail::kMaxFloatTextLength);
}

TEST_CASE("JSON strings: quotes, backslashes, control characters and '<' escaped, UTF-8 kept",
          "[detail][text]") {
  using glint::detail::json_string;
  CHECK(json_string("") == "\"\"");
  CHECK(json_string("a \"b\" c\\d") == "\"a \\\"b\\\" c\\\\d\"");
  CHECK(json_string(std::string_view("\n\t\x01\x1f\x7f", 5)) ==
        "\"\\u000a\\u0009\\u0001\\u001f\\u007f\"");
  CHECK(json_string(std::string_view("\0", 1)) == "\"\\u0000\"");
  CHECK(json_string("</script>") == "\"\\u003c/script>\"");
  CHECK(json_string("caf\xc3\xa9 ~") == "\"caf\xc3\xa9 ~\"");
}
