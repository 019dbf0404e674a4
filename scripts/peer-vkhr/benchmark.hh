// strandbench's replacement for vkhr's include/vkhr/benchmark.hh (copied over it by
// scripts/peer-vkhr.sh): one benchmark case, the scene given on vkhr's command line, in place of
// vkhr's fixed sweep over its own (large-file) ponytail and bear scenes. The case is read from
// the environment: VKHR_SB_SCENE (the .vkhr file, as passed to vkhr), VKHR_SB_WIDTH,
// VKHR_SB_HEIGHT, VKHR_SB_DISTANCE (camera to look-at point), VKHR_SB_RENDERER (rasterizer or
// raymarcher), VKHR_SB_STEPS (raymarching samples). vkhr's own timing, CSV and screenshot code
// run unchanged.
#ifndef VKHR_BENCHMARK_HH
#define VKHR_BENCHMARK_HH

#include <vkhr/rasterizer.hh>

#include <cstdlib>
#include <string>

namespace vkhr {
    class Benchmark final {
    public:
        static void construct(Rasterizer& rasterizer);
    };

    inline void Benchmark::construct(Rasterizer& rasterizer) {
        auto env = [](const char* name, const char* fallback) {
            const char* v = std::getenv(name);
            return std::string { v ? v : fallback };
        };
        const bool raymarch = env("VKHR_SB_RENDERER", "rasterizer") == "raymarcher";
        rasterizer.append_benchmark({ raymarch ? "strandbench raymarcher" : "strandbench rasterizer",
                                      env("VKHR_SB_SCENE", ""),
                                      std::atoi(env("VKHR_SB_WIDTH", "1280").c_str()),
                                      std::atoi(env("VKHR_SB_HEIGHT", "720").c_str()),
                                      raymarch ? vkhr::Renderer::Raymarcher : vkhr::Renderer::Rasterizer,
                                      static_cast<float>(std::atof(env("VKHR_SB_DISTANCE", "226").c_str())),
                                      1.0f,
                                      std::atoi(env("VKHR_SB_STEPS", "512").c_str()) });
    }
}

#endif
