// dev/compare_builds.sh's timer: loads two builds' paired_driver (each with its own copy of
// the core library, in its own link namespace) and times them in turns of a few hundred
// samples, so that both see the same machine: on a shared VM whose speed drifts by tens of
// percent within minutes, the ratio of neighbouring turns still resolves 1-2 %.
// Usage: paired_compare BASE_DRIVER.so NEW_DRIVER.so SOURCE_DIR [SIMD_TARGET] [TURNS]
#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

struct Driver {
  int (*case_count)();
  const char* (*case_name)(int);
  void* (*make_case)(int, const char*, const char*);
  double (*step)(void*, int);
  const char* (*simd_target)();
};

Driver load(const char* path) {
  void* lib = dlmopen(LM_ID_NEWLM, path, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    std::fprintf(stderr, "paired_compare: %s\n", dlerror());
    std::exit(2);
  }
  Driver d;
  d.case_count = reinterpret_cast<int (*)()>(dlsym(lib, "paired_case_count"));
  d.case_name = reinterpret_cast<const char* (*)(int)>(dlsym(lib, "paired_case_name"));
  d.make_case = reinterpret_cast<void* (*)(int, const char*, const char*)>(dlsym(lib, "paired_make_case"));
  d.step = reinterpret_cast<double (*)(void*, int)>(dlsym(lib, "paired_step"));
  d.simd_target = reinterpret_cast<const char* (*)()>(dlsym(lib, "paired_simd_target"));
  if (!d.case_count || !d.case_name || !d.make_case || !d.step || !d.simd_target) {
    std::fprintf(stderr, "paired_compare: %s lacks the paired_* functions\n", path);
    std::exit(2);
  }
  return d;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s BASE_DRIVER.so NEW_DRIVER.so SOURCE_DIR [SIMD_TARGET] [TURNS]\n", argv[0]);
    return 2;
  }
  const char* target = argc > 4 ? argv[4] : "AVX2";
  const int turns = argc > 5 ? std::atoi(argv[5]) : 61;
  const Driver base = load(argv[1]), next = load(argv[2]);
  // Samples per turn: ~1 ms of each case.
  const int samples[] = {400, 200, 500, 1500};
  for (int c = 0; c < base.case_count(); ++c) {
    void* a = base.make_case(c, argv[3], target);
    void* b = next.make_case(c, argv[3], target);
    base.step(a, 2000);  // past the start-up
    next.step(b, 2000);
    std::vector<double> ta, tb, ratio;
    for (int t = 0; t < turns; ++t) {
      const double x = base.step(a, samples[c]), y = next.step(b, samples[c]);
      ta.push_back(x);
      tb.push_back(y);
      ratio.push_back(x / y);
    }
    // Real-time factor at 10 kHz: 1e5 / (ns per sample).
    std::printf(
        "%-27s %s | base %6.1fx (best %6.1fx) | new %6.1fx (best %6.1fx) | new/base speed %.3f (quartiles %.3f-%.3f)\n",
        base.case_name(c), next.simd_target(), 1e5 / quantile(ta, 0.5), 1e5 / quantile(ta, 0.0),
        1e5 / quantile(tb, 0.5), 1e5 / quantile(tb, 0.0), quantile(ratio, 0.5), quantile(ratio, 0.25),
        quantile(ratio, 0.75));
  }
  return 0;
}
