// Copy of shared/baselines/scripts/embree_bench.cpp that takes the mesh and ray files as
// arguments 4 and 5, so benches/mesh_bvh.rs can hand Embree the dragon and incoherent rays.
// Embree 3 primary-ray benchmark on the shared terrain mesh + rays.
// Build: g++ -O3 -march=native -std=c++17 embree_bench.cpp -o /tmp/perf/embree_bench -lembree3 -lpthread
// Usage: mesh_embree <threads> <quality:low|medium|high> [reps] [mesh.bin] [rays.bin] [what]
//   what: all (default), single (rtcIntersect1 and rtcOccluded1 only), intersect1.
//   threads: Embree device threads (BVH build) and number of tracing threads.
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

static double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// CPU seconds used by the whole process (every thread): on a shared machine, the steadier
// figure for one-thread runs.
static double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}
static double last_cpu = 0;

struct Result { long hits; double tsum; };

static std::vector<float> rays; static unsigned W, H;

template <class F>
static double run_parallel(int nthreads, unsigned rows_per_task, F&& f) {
  // f(y0, y1) traces rows [y0, y1)
  std::atomic<unsigned> next{0};
  double t0 = now(), c0 = cpu_now();
  auto worker = [&]() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);          // as recommended by Embree
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    for (;;) {
      unsigned y0 = next.fetch_add(rows_per_task);
      if (y0 >= H) break;
      f(y0, std::min(H, y0 + rows_per_task));
    }
  };
  if (nthreads == 1) worker();
  else {
    std::vector<std::thread> ts;
    for (int i = 0; i < nthreads; i++) ts.emplace_back(worker);
    for (auto& t : ts) t.join();
  }
  last_cpu = cpu_now() - c0;
  return now() - t0;
}

int main(int argc, char** argv) {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  int nthreads = argc > 1 ? atoi(argv[1]) : 1;
  const char* mesh_path = argc > 4 ? argv[4] : "/tmp/perf/terrain.bin";
  const char* rays_path = argc > 5 ? argv[5] : "/tmp/perf/rays.bin";
  std::string q = argc > 2 ? argv[2] : "medium";
  int reps = argc > 3 ? atoi(argv[3]) : 5;
  std::string what = argc > 6 ? argv[6] : "all";
  RTCBuildQuality quality = q == "low" ? RTC_BUILD_QUALITY_LOW : q == "high" ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;

  FILE* fm = fopen(mesh_path, "rb");
  unsigned nv, nt;
  if (!fm || fread(&nv, 4, 1, fm) != 1 || fread(&nt, 4, 1, fm) != 1) { fprintf(stderr, "mesh\n"); return 1; }
  std::vector<float> V(nv * 3); std::vector<unsigned> I(nt * 3);
  if (fread(V.data(), 4, V.size(), fm) != V.size() || fread(I.data(), 4, I.size(), fm) != I.size()) return 1;
  fclose(fm);
  FILE* fr = fopen(rays_path, "rb");
  if (!fr || fread(&W, 4, 1, fr) != 1 || fread(&H, 4, 1, fr) != 1) return 1;
  rays.resize(size_t(W) * H * 6);
  if (fread(rays.data(), 4, rays.size(), fr) != rays.size()) return 1;
  fclose(fr);

  std::string cfg = "threads=" + std::to_string(nthreads) + (getenv("EMBREE_VERBOSE") ? ",verbose=1" : "");
  RTCDevice dev = rtcNewDevice(cfg.c_str());
  if (!dev) { fprintf(stderr, "device error\n"); return 1; }

  // Build (timed; best of 3 builds from the same buffers)
  double best_build = 1e30, best_build_cpu = 1e30; RTCScene scene = nullptr;
  for (int b = 0; b < 3; b++) {
    if (scene) rtcReleaseScene(scene);
    double t0 = now(), c0 = cpu_now();
    scene = rtcNewScene(dev);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(g, quality);
    float* vb = (float*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, nv);
    unsigned* ib = (unsigned*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, nt);
    memcpy(vb, V.data(), V.size() * 4); memcpy(ib, I.data(), I.size() * 4);
    rtcCommitGeometry(g); rtcAttachGeometry(scene, g); rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    best_build = std::min(best_build, now() - t0);
    best_build_cpu = std::min(best_build_cpu, cpu_now() - c0);
  }
  printf("embree %s quality=%s threads=%d tris=%u build_best_of_3=%.3f s cpu_best_of_3=%.3f s\n",
         rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION) ? "3" : "?", q.c_str(), nthreads, nt, best_build,
         best_build_cpu);

  const size_t N = size_t(W) * H;
  std::vector<float> tout(N);

  std::vector<double> cpu;  // the CPU seconds of the passes being reported
  auto report = [&](const char* name, std::vector<double>& ts) {
    std::sort(ts.begin(), ts.end());
    std::sort(cpu.begin(), cpu.end());
    long hits = 0; double tsum = 0;
    for (size_t i = 0; i < N; i++) if (std::isfinite(tout[i])) { hits++; tsum += tout[i]; }
    printf("  %-22s best %.4f s (%.2f Mrays/s)  median %.4f s (%.2f Mrays/s)  cpu best %.4f s (%.2f Mrays/s)  cpu median %.4f s (%.2f Mrays/s)  hits=%ld tsum=%.3f\n", name,
           ts[0], N / ts[0] / 1e6, ts[ts.size() / 2], N / ts[ts.size() / 2] / 1e6, cpu[0], N / cpu[0] / 1e6,
           cpu[cpu.size() / 2], N / cpu[cpu.size() / 2] / 1e6, hits, tsum);
    cpu.clear();
  };

  // ---- rtcIntersect1 ----
  {
    std::vector<double> ts;
    for (int r = 0; r < reps + 1; r++) {
      double t = run_parallel(nthreads, 8, [&](unsigned y0, unsigned y1) {
        RTCIntersectContext ctx; rtcInitIntersectContext(&ctx);
        for (unsigned y = y0; y < y1; y++) for (unsigned x = 0; x < W; x++) {
          size_t i = size_t(y) * W + x; const float* R = &rays[i * 6];
          RTCRayHit rh;
          rh.ray.org_x = R[0]; rh.ray.org_y = R[1]; rh.ray.org_z = R[2];
          rh.ray.dir_x = R[3]; rh.ray.dir_y = R[4]; rh.ray.dir_z = R[5];
          rh.ray.tnear = 0.f; rh.ray.tfar = INFINITY; rh.ray.time = 0.f; rh.ray.mask = ~0u; rh.ray.id = 0; rh.ray.flags = 0;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID; rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(scene, &ctx, &rh);
          tout[i] = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : INFINITY;
        }
      });
      if (r > 0) { ts.push_back(t); cpu.push_back(last_cpu); }  // first run = warm-up
    }
    report("rtcIntersect1", ts);
  }

  if (what == "all") {
  // ---- packets: 4 (2x2), 8 (4x2), 16 (4x4) tiles ----
  auto packet = [&](auto tag, int tw, int th, const char* name, bool coherent) {
    using RH = decltype(tag);
    constexpr int K = sizeof(((RH*)nullptr)->ray.org_x) / sizeof(float);
    std::vector<double> ts;
    for (int r = 0; r < reps + 1; r++) {
      double t = run_parallel(nthreads, 8, [&](unsigned y0, unsigned y1) {
        RTCIntersectContext ctx; rtcInitIntersectContext(&ctx);
        if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        alignas(64) int valid[K]; for (int k = 0; k < K; k++) valid[k] = -1;
        alignas(64) RH rh;
        for (unsigned ty = y0; ty < y1; ty += th) for (unsigned tx = 0; tx < W; tx += tw) {
          for (int k = 0; k < K; k++) {
            unsigned x = tx + k % tw, y = ty + k / tw;
            const float* R = &rays[(size_t(y) * W + x) * 6];
            rh.ray.org_x[k] = R[0]; rh.ray.org_y[k] = R[1]; rh.ray.org_z[k] = R[2];
            rh.ray.dir_x[k] = R[3]; rh.ray.dir_y[k] = R[4]; rh.ray.dir_z[k] = R[5];
            rh.ray.tnear[k] = 0.f; rh.ray.tfar[k] = INFINITY; rh.ray.time[k] = 0.f; rh.ray.mask[k] = ~0u;
            rh.ray.id[k] = k; rh.ray.flags[k] = 0;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID; rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
          }
          if constexpr (K == 4) rtcIntersect4(valid, scene, &ctx, &rh);
          else if constexpr (K == 8) rtcIntersect8(valid, scene, &ctx, &rh);
          else rtcIntersect16(valid, scene, &ctx, &rh);
          for (int k = 0; k < K; k++) {
            unsigned x = tx + k % tw, y = ty + k / tw;
            tout[size_t(y) * W + x] = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar[k] : INFINITY;
          }
        }
      });
      if (r > 0) { ts.push_back(t); cpu.push_back(last_cpu); }
    }
    report(name, ts);
  };
  packet(RTCRayHit4{}, 2, 2, "rtcIntersect4 (2x2)", true);
  packet(RTCRayHit8{}, 4, 2, "rtcIntersect8 (4x2)", true);
  packet(RTCRayHit16{}, 4, 4, "rtcIntersect16 (4x4)", true);

  // ---- ray stream rtcIntersect1M, one row (1920 rays) per call, coherent ----
  {
    std::vector<double> ts;
    for (int r = 0; r < reps + 1; r++) {
      double t = run_parallel(nthreads, 8, [&](unsigned y0, unsigned y1) {
        RTCIntersectContext ctx; rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        std::vector<RTCRayHit> rh(W);
        for (unsigned y = y0; y < y1; y++) {
          for (unsigned x = 0; x < W; x++) {
            const float* R = &rays[(size_t(y) * W + x) * 6];
            RTCRayHit& h = rh[x];
            h.ray.org_x = R[0]; h.ray.org_y = R[1]; h.ray.org_z = R[2];
            h.ray.dir_x = R[3]; h.ray.dir_y = R[4]; h.ray.dir_z = R[5];
            h.ray.tnear = 0.f; h.ray.tfar = INFINITY; h.ray.time = 0.f; h.ray.mask = ~0u; h.ray.id = x; h.ray.flags = 0;
            h.hit.geomID = RTC_INVALID_GEOMETRY_ID; h.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcIntersect1M(scene, &ctx, rh.data(), W, sizeof(RTCRayHit));
          for (unsigned x = 0; x < W; x++)
            tout[size_t(y) * W + x] = rh[x].hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh[x].ray.tfar : INFINITY;
        }
      });
      if (r > 0) { ts.push_back(t); cpu.push_back(last_cpu); }
    }
    report("rtcIntersect1M (row)", ts);
  }
  }  // what == "all"

  // ---- occlusion (shadow-ray style any-hit) with rtcOccluded1 for the same rays ----
  if (what != "intersect1") {
    std::vector<double> ts;
    for (int r = 0; r < reps + 1; r++) {
      double t = run_parallel(nthreads, 8, [&](unsigned y0, unsigned y1) {
        RTCIntersectContext ctx; rtcInitIntersectContext(&ctx);
        for (unsigned y = y0; y < y1; y++) for (unsigned x = 0; x < W; x++) {
          size_t i = size_t(y) * W + x; const float* R = &rays[i * 6];
          RTCRay ray;
          ray.org_x = R[0]; ray.org_y = R[1]; ray.org_z = R[2];
          ray.dir_x = R[3]; ray.dir_y = R[4]; ray.dir_z = R[5];
          ray.tnear = 0.f; ray.tfar = INFINITY; ray.time = 0.f; ray.mask = ~0u; ray.id = 0; ray.flags = 0;
          rtcOccluded1(scene, &ctx, &ray);
          tout[i] = ray.tfar < 0 ? 1.f : INFINITY;  // tfar = -inf when occluded
        }
      });
      if (r > 0) { ts.push_back(t); cpu.push_back(last_cpu); }
    }
    report("rtcOccluded1 (any-hit)", ts);
  }

  rtcReleaseScene(scene);
  rtcReleaseDevice(dev);
  return 0;
}
