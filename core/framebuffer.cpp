// Framebuffer: named planar channels.
#include "core/framebuffer.h"

#include <algorithm>

#include "core/error.h"

namespace rc {

const char* channelTypeName(ChannelType type) {
  return type == ChannelType::kUint ? "UINT" : "FLOAT";
}

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0) {
    throw internalError("framebuffer size must be positive, got " + std::to_string(width) + "x" +
                        std::to_string(height));
  }
}

float* Framebuffer::addFloat(const std::string& name, float fill) {
  if (find(name)) throw internalError("duplicate channel " + name);
  Channel c{name, ChannelType::kFloat, {}, {}};
  c.floats.assign(pixelCount(), fill);
  channels_.push_back(std::move(c));
  return channels_.back().floats.data();
}

std::uint32_t* Framebuffer::addUint(const std::string& name, std::uint32_t fill) {
  if (find(name)) throw internalError("duplicate channel " + name);
  Channel c{name, ChannelType::kUint, {}, {}};
  c.uints.assign(pixelCount(), fill);
  channels_.push_back(std::move(c));
  return channels_.back().uints.data();
}

void Framebuffer::recycle(int width, int height, const std::vector<std::string>& keep) {
  if (width <= 0 || height <= 0) {
    throw internalError("framebuffer size must be positive, got " + std::to_string(width) + "x" +
                        std::to_string(height));
  }
  if (width != width_ || height != height_) channels_.clear();
  width_ = width;
  height_ = height;
  std::deque<Channel> kept;
  for (Channel& c : channels_) {
    if (std::find(keep.begin(), keep.end(), c.name) != keep.end()) kept.push_back(std::move(c));
  }
  channels_ = std::move(kept);
  attributes.clear();
}

Channel& Framebuffer::reuseChannel(const std::string& name, ChannelType type) {
  Channel* c = find(name);
  if (!c) {
    channels_.push_back({name, type, {}, {}});
    return channels_.back();
  }
  if (c->type != type) throw internalError("channel " + name + " exists with another type");
  return *c;
}

float* Framebuffer::reuseFloat(const std::string& name) {
  Channel& c = reuseChannel(name, ChannelType::kFloat);
  c.floats.resize(pixelCount());
  return c.floats.data();
}

std::uint32_t* Framebuffer::reuseUint(const std::string& name) {
  Channel& c = reuseChannel(name, ChannelType::kUint);
  c.uints.resize(pixelCount());
  return c.uints.data();
}

const Channel* Framebuffer::find(const std::string& name) const {
  for (const Channel& c : channels_) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

Channel* Framebuffer::find(const std::string& name) {
  for (Channel& c : channels_) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

}  // namespace rc
