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
  PlaneVector<float> floats;  // width*height values when kFloat
  PlaneVector<std::uint32_t> uints;  // ... when kUint
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

  // For renderers that write every pixel of every channel, frame after frame, into the same
  // framebuffer: recycle() sets the size (dropping every channel when it changes), drops the
  // channels not named in `keep` and clears the header attributes; reuseFloat/reuseUint then
  // return a kept channel's plane, or add the channel, with contents unspecified. A second
  // frame of the same size so touches no new memory (page faults cost more than rendering).
  void recycle(int width, int height, const std::vector<std::string>& keep);
  float* reuseFloat(const std::string& name);
  std::uint32_t* reuseUint(const std::string& name);

  const Channel* find(const std::string& name) const;
  Channel* find(const std::string& name);
  const std::deque<Channel>& channels() const { return channels_; }

  // Header attributes written as OpenEXR string attributes (provenance: renderer, mode, ...).
  std::map<std::string, std::string> attributes;

 private:
  Channel& reuseChannel(const std::string& name, ChannelType type);

  int width_ = 0;
  int height_ = 0;
  std::deque<Channel> channels_;
};

}  // namespace rc
