// Bit-for-bit comparison of two framebuffers, for the determinism tests.
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include "core/framebuffer.h"

namespace rc::testing {

// Names of the channels that differ in any bit, or that only one of the two has; also
// "<size>" when the sizes differ. Empty when the two are identical.
inline std::vector<std::string> differingChannels(const Framebuffer& a, const Framebuffer& b) {
  if (a.width() != b.width() || a.height() != b.height()) return {"<size>"};
  std::vector<std::string> differ;
  for (const Channel& ca : a.channels()) {
    const Channel* cb = b.find(ca.name);
    const bool same = cb && cb->type == ca.type &&
                      (ca.type == ChannelType::kUint
                           ? cb->uints.size() == ca.uints.size() &&
                                 std::memcmp(ca.uints.data(), cb->uints.data(), ca.uints.size() * 4) == 0
                           : cb->floats.size() == ca.floats.size() &&
                                 std::memcmp(ca.floats.data(), cb->floats.data(), ca.floats.size() * 4) == 0);
    if (!same) differ.push_back(ca.name);
  }
  for (const Channel& cb : b.channels()) {
    if (!a.find(cb.name)) differ.push_back(cb.name);
  }
  return differ;
}

}  // namespace rc::testing
