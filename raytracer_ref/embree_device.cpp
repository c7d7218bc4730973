// Embree device and scene wrappers with deferred error reporting.
#include "raytracer_ref/embree_device.h"

#include "core/error.h"

namespace rc {

EmbreeDevice::EmbreeDevice(const std::string& config) {
  device_ = rtcNewDevice(config.c_str());
  if (!device_) {
    throw internalError("Embree: cannot create a device with config '" + config +
                        "' (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
  // Never throw through Embree's C frames: record the first error and return.
  auto* device = static_cast<EmbreeDevice*>(self);
  std::lock_guard<std::mutex> lock(device->mutex_);
  if (device->firstError_.empty()) {
    device->firstError_ = "error " + std::to_string(int(code)) + ": " + (message ? message : "");
  }
}

void EmbreeDevice::check(const char* during) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!firstError_.empty()) {
    const std::string error = firstError_;
    firstError_.clear();
    throw internalError(std::string("Embree failed during ") + during + ": " + error);
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
