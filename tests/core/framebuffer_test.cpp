// Framebuffer channel storage.
#include <gtest/gtest.h>

#include "core/framebuffer.h"

namespace rc {
namespace {

// Regression (found by ASan): addPreview held a Channel pointer while adding R, G, B, and the
// channel container reallocated under it.
TEST(Framebuffer, ChannelPointersStayValidWhileChannelsAreAdded) {
  Framebuffer fb(4, 4);
  fb.addUint("tri.id", 7);
  const Channel* id = fb.find("tri.id");
  const std::uint32_t* plane = id->uints.data();
  for (int i = 0; i < 100; ++i) fb.addFloat("extra." + std::to_string(i));
  EXPECT_EQ(fb.find("tri.id"), id);
  EXPECT_EQ(id->uints.data(), plane);
  EXPECT_EQ(id->uints[15], 7u);
}

TEST(Framebuffer, DuplicateChannelNamesAreRefused) {
  Framebuffer fb(2, 2);
  fb.addFloat("a");
  EXPECT_ANY_THROW(fb.addFloat("a"));
  EXPECT_ANY_THROW(fb.addUint("a"));
}

}  // namespace
}  // namespace rc
