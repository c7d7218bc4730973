// A framebuffer of named, typed channels (planar, row 0 at the top) plus header attributes.
// It is the only currency between the renderers, compare and the EXR files: nothing else
// knows how pixels are laid out on disk.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "core/plane_allocator.h"

namespace rc {

enum class ChannelType { kUint, kFloat };

const char* channelTypeName(ChannelType type);

struct Channel {
  std::string name;                // OpenEXR layer.channel name, e.g. "bary.b0"
  ChannelType type;                // which of the two planes below is in use
  std::vector<float, PlaneAllocator<float>> floats;  // width*height values when kFloat
  std::vector<std::uint32_t, PlaneAllocator<std::uint32_t>> uints;  // ... when kUint
};

class Framebuffer {
 public:
  Framebuffer() = default;
  Framebuffer(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixelCount() const { return std::size_t(width_) * std::size_t(height_); }

  // Adds a channel filled with `fill` and returns its plane. Throws if the name exists.
  // Channels live in a deque: pointers to a Channel and to its plane stay valid while further
  // channels are added (ASan caught a vector reallocating under a held Channel pointer).
  float* addFloat(const std::string& name, float fill = 0.0f);
  std::uint32_t* addUint(const std::string& name, std::uint32_t fill = 0);

  const Channel* find(const std::string& name) const;
  Channel* find(const std::string& name);
  const std::deque<Channel>& channels() const { return channels_; }

  // Header attributes written as OpenEXR string attributes (provenance: renderer, mode, ...).
  std::map<std::string, std::string> attributes;

 private:
  int width_ = 0;
  int height_ = 0;
  std::deque<Channel> channels_;
};

}  // namespace rc
