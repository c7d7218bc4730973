// Framebuffer: named planar channels.
#include "core/framebuffer.h"

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
