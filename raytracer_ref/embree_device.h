// RAII wrappers over Embree's device and scene, following the tutorials' sequence
// (device -> scene -> geometry -> commit -> intersect). Embree reports errors through a C
// callback, which only records them; check() raises them as rc::Error after the call returns.
#pragma once

#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace rc {

class EmbreeDevice {
 public:
  explicit EmbreeDevice(const std::string& config);
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }
  // Throws the first error recorded since the last check, naming `during`: outOfMemory
  // (exit 4) where Embree ran out of memory, else internalError (exit 5).
  void check(const char* during);

 private:
  static void onError(void* self, RTCError code, const char* message);
  RTCDevice device_ = nullptr;
  std::mutex mutex_;
  RTCError firstCode_ = RTC_ERROR_NONE;
  std::string firstError_;
};

class EmbreeScene {
 public:
  EmbreeScene(EmbreeDevice& device, RTCSceneFlags flags);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

}  // namespace rc
