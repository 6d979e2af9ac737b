// Embree's BVH self-collision (rtcCollide, Embree 3) on the spheres' bounding
// boxes as user-geometry primitives, then the exact sphere test in the
// collide callback (compiled only when Embree is found: HGRID_HAVE_EMBREE).
//
// Embree builds and traverses with its own threads (TBB in Debian's build),
// as many as the device's "threads=N" config allows. Its boxes are floats:
// each bound is rounded outward, so that no overlapping pair is lost; the
// exact test is in double. For a self-collision (the same scene twice)
// rtcCollide reports every unordered pair of primitives in both orders and
// no primitive with itself (checked against a brute-force count), so only
// the order primID0 < primID1 is kept. Periodic boxes: the images of
// periodic_images.hpp. The scene is built at RTC_BUILD_QUALITY_LOW (Embree's
// setting for scenes rebuilt every frame; on the figure-11 packing at
// N = 1e5, build + collide take 0.095 s against 0.174 s at the default
// MEDIUM, same candidates). Timed: images, scene build (rtcCommitScene) and
// rtcCollide; the scene's release is not.
#pragma once
#ifdef HGRID_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/detail/periodic_images.hpp"
#include "hgridlab/grid/geometry.hpp"

namespace hgrid::bench {

/// An Embree device with `threads` threads (0: Embree's default, all cores),
/// kept for every timed collision.
class EmbreeCollider {
 public:
  explicit EmbreeCollider(int threads) : threads_(threads) {
    const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("rtcNewDevice(\"" + config + "\") failed");
  }
  ~EmbreeCollider() { rtcReleaseDevice(device_); }
  EmbreeCollider(const EmbreeCollider&) = delete;
  EmbreeCollider& operator=(const EmbreeCollider&) = delete;

  int threads() const { return threads_; }
  /// "TBB", "internal" or "PPL": who runs Embree's threads.
  std::string tasking() const {
    switch (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_TASKING_SYSTEM)) {
      case 0: return "internal";
      case 1: return "TBB";
      case 2: return "PPL";
      default: return "unknown";
    }
  }

  template <int D, Boundary B>
  PeerRun pairs(std::span<const Sphere<D>> s, const Extent<D>& box) {
    static_assert(D == 2 || D == 3);
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    std::vector<Image<D>> img;
    make_images<D, B>(s, box, img);
    RTCScene scene = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_LOW);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_LOW);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(img.size()));
    rtcSetGeometryUserData(geom, img.data());
    rtcSetGeometryBoundsFunction(geom, &bounds<D>, nullptr);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    Hits<D> hits{img.data(), {0}};
    rtcCollide(scene, scene, &collide<D>, &hits);
    const double sec = std::chrono::duration<double>(Clock::now() - t0).count();
    rtcReleaseScene(scene);
    if (const RTCError e = rtcGetDeviceError(device_); e != RTC_ERROR_NONE)
      throw std::runtime_error("Embree error code " + std::to_string(static_cast<int>(e)));
    return {sec, hits.pairs.load()};
  }

 private:
  template <int D>
  struct Hits {
    const Image<D>* img;
    std::atomic<std::uint64_t> pairs;
  };

  template <int D>
  static void bounds(const RTCBoundsFunctionArguments* a) {
    const Image<D>& m = static_cast<const Image<D>*>(a->geometryUserPtr)[a->primID];
    RTCBounds* b = a->bounds_o;
    b->lower_x = round_outward<float>(m.x[0] - m.r, -1), b->upper_x = round_outward<float>(m.x[0] + m.r, 1);
    b->lower_y = round_outward<float>(m.x[1] - m.r, -1), b->upper_y = round_outward<float>(m.x[1] + m.r, 1);
    if constexpr (D == 3) {
      b->lower_z = round_outward<float>(m.x[2] - m.r, -1), b->upper_z = round_outward<float>(m.x[2] + m.r, 1);
    } else {
      b->lower_z = b->upper_z = 0.0f;
    }
  }

  /// Called from Embree's threads, a batch at a time: one atomic add per batch.
  template <int D>
  static void collide(void* user, RTCCollision* c, unsigned n) {
    auto* h = static_cast<Hits<D>*>(user);
    std::uint64_t found = 0;
    for (unsigned k = 0; k < n; ++k)
      if (c[k].primID0 < c[k].primID1 && counts_as_contact<D>(h->img + c[k].primID0, h->img + c[k].primID1)) ++found;
    if (found) h->pairs.fetch_add(found, std::memory_order_relaxed);
  }

  RTCDevice device_;
  int threads_;
};

}  // namespace hgrid::bench
#endif
