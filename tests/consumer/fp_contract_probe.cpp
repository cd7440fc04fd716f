// Prints whether this translation unit fuses multiplies and adds, as glint::multiply_add_is_fused
// sees it: "fused" or "separate". tests/consumer/fp_contract_probe.cmake compiles it with
// -ffp-contract=off and =fast for a CPU with FMA and requires the two answers.
#include <cstdio>

#include "glint/fp_contract.hpp"

int main() {
  std::puts(glint::multiply_add_is_fused() ? "fused" : "separate");
  return 0;
}
