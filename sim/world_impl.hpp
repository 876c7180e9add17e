#pragma once

// World's private state (sim/world.hpp's World::Impl), shared by world.cpp (building the scene,
// single rays and packets) and world_batch.cpp (ray batches). Private to sim (names Embree; not
// installed).

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "casmap/sim/world.hpp"
#include "casmap/sim/world_shapes.hpp"

namespace casmap::sim {
namespace detail {

using DevicePtr = std::unique_ptr<RTCDeviceTy, decltype(&rtcReleaseDevice)>;
using ScenePtr = std::unique_ptr<RTCSceneTy, decltype(&rtcReleaseScene)>;

// Embree reports errors through a C callback, where throwing is not allowed: the callback
// records the first error and Check() turns it into an exception at the call site.
struct ErrorSink {
    std::mutex mutex;
    RTCError code = RTC_ERROR_NONE;
    std::string message;

    void Check(const std::string& context) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (code != RTC_ERROR_NONE) {
            const std::string text = "embree error " + std::to_string(static_cast<int>(code)) +
                                     " (" + message + ") while " + context;
            code = RTC_ERROR_NONE;
            throw std::runtime_error(text);
        }
    }
};

}  // namespace detail

struct World::Impl {
    // Members are destroyed bottom-up: the scene goes first, then the device, and only then
    // the cylinders it points to and the error sink its callback writes to.
    detail::ErrorSink errors;
    std::vector<std::unique_ptr<detail::Cylinder>> cylinders;  // user data, stable addresses
    std::vector<float> reflectivity;                           // per geometry id = object index
    std::vector<std::uint8_t> retro;                           // per geometry id: retro-reflector
    detail::DevicePtr device{nullptr, &rtcReleaseDevice};
    detail::ScenePtr scene{nullptr, &rtcReleaseScene};

    void AddTriangles(const detail::TriangleSoup& soup, unsigned int id, const std::string& name);
    void AddCylinder(const core::CylinderShape& shape,
                     const core::Pose& pose,
                     unsigned int id,
                     const std::string& name);
    Hit MakeHit(unsigned int geom_id,
                float tfar,
                const Eigen::Vector3f& ng,
                const Eigen::Vector3f& dir) const;
};

}  // namespace casmap::sim
