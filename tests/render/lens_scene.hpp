#pragma once
// A test scene's camera made a thin lens: the statistical comparisons of the estimators run again
// with depth of field, where every camera ray and every join to the camera goes through a lens
// point drawn for it.

#include <string>

namespace glint_test {

/// `text` with `lens_keys` ("aperture=A focus=F") added to its camera statement.
inline std::string through_lens(std::string text, const std::string& lens_keys) {
  const std::size_t camera = text.find("\ncamera");
  const std::size_t end = text.find('\n', camera + 1);
  text.insert(end, " " + lens_keys);
  return text;
}

}  // namespace glint_test
