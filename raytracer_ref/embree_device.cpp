// Embree device and scene wrappers with deferred error reporting.
#include "raytracer_ref/embree_device.h"

#include <string>

#include "core/error.h"

namespace rc {

namespace {

// Embree's error code in words (rtcore_device.h).
std::string describe(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "error " + std::to_string(int(code));
  }
}

// Out of memory is a resource that ran out, like a full disk (exit 4); any other error of
// Embree's is one no input explains (exit 5).
Error embreeError(RTCError code, const std::string& what) {
  if (code == RTC_ERROR_OUT_OF_MEMORY) return outOfMemory("Embree", what);
  return internalError("Embree: " + describe(code) + " " + what);
}

}  // namespace

EmbreeDevice::EmbreeDevice(const std::string& config) {
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw embreeError(rtcGetDeviceError(nullptr), "creating its device (config '" + config + "')");
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
  // Never throw through Embree's C frames: record the first error and return.
  auto* device = static_cast<EmbreeDevice*>(self);
  std::lock_guard<std::mutex> lock(device->mutex_);
  if (device->firstError_.empty()) {
    device->firstCode_ = code;
    device->firstError_ = message && *message ? message : describe(code);
  }
}

void EmbreeDevice::check(const char* during) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!firstError_.empty()) {
    const std::string error = firstError_;
    firstError_.clear();
    throw embreeError(firstCode_, std::string("during ") + during + " (" + error + ")");
  }
}

EmbreeScene::EmbreeScene(EmbreeDevice& device, RTCSceneFlags flags) {
  scene_ = rtcNewScene(device.get());
  device.check("rtcNewScene");
  rtcSetSceneFlags(scene_, flags);
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
}

}  // namespace rc
