#pragma once
// Fuzz-only: the input bytes of a libFuzzer target read one at a time, 0 once they run out, so
// every input (even an empty one) decodes to some case.

#include <cstddef>
#include <cstdint>

namespace scenevis
{
namespace fuzz
{

struct Bytes
{
  const std::uint8_t* data;
  std::size_t size;
  std::size_t at = 0;
  bool more() const { return at < size; }
  unsigned next() { return at < size ? data[at++] : 0u; }
  /// The next byte as a fraction in [0, 1].
  double unit() { return this->next() / 255.0; }
};

} // namespace fuzz
} // namespace scenevis
