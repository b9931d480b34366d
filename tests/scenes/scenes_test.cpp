// The sample scenes (samples/scenes/*.sm2cs, the demos of ../shared/scenes.md) replayed through
// the library, the way D3D9 conformance tests check a rendering: every scene replays without a
// refused call, gives the same bytes with 1 and 3 threads, on the reference and block paths and with
// the interpreter and the JIT, and the probe pixels of
// samples/scenes/probes.txt (expected colours derived by hand from each scene's geometry and
// D3D9's rules; the reason is written beside each probe) hold their colour. Golden images
// (tests/scenes/golden/<scene>/<image>.png) were saved only after the probes passed and the
// frames were looked at; they guard every other pixel against regressions. Regenerate them with
// SM2_UPDATE_GOLDENS=1 after a deliberate change, and look at the new ones before committing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sm2/runtime/stream_assembler.h"
#include "sm2/runtime/command_stream.h"
#include "sm2/runtime/image_io.h"
#include "sm2/runtime/replay.h"

namespace sm2::runtime {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(SM2_SOURCE_DIR) / "samples" / "scenes";
const std::filesystem::path kGoldens = std::filesystem::path(SM2_SOURCE_DIR) / "tests" / "scenes" / "golden";

// Every Present and SaveSurface of a replay, kept in memory by file name.
struct Replayed {
    std::map<std::string, Surface> images;
    ReplayResult result;
    std::unique_ptr<Device> device;  // as the stream left it (surfaces, textures)
};

Replayed replay_scene(const std::string& file, unsigned threads, bool reference_paths = false) {
    Replayed out;
    std::ifstream in(kScenes / file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    cs::TextOptions text_options;
    text_options.file_name = file;
    text_options.base_dir = kScenes.string();
    auto parsed = cs::parse_text(text.str(), text_options);
    EXPECT_TRUE(parsed.ok()) << (parsed.error ? parsed.error->to_string() : "");
    if (!parsed.ok()) return out;
    DeviceOptions options;
    options.threads = threads;
    options.reference_paths = reference_paths;
    // The reference run interprets; every other run takes the JIT (where the build has one).
    options.engine = reference_paths ? DeviceOptions::Engine::Interpreter : DeviceOptions::Engine::Jit;
    options.output_dir = "frames";  // any name: write_image keeps the surfaces instead
    options.write_image = [&out](const Surface& surface, const std::string& path) {
        out.images[std::filesystem::path(path).filename().string()] = surface;
    };
    out.device = std::make_unique<Device>(options);
    ReplayOptions replay_options;
    replay_options.file_name = file;
    replay_options.base_dir = kScenes.string();
    replay_options.assembler = runtime::stream_assembler();
    out.result = replay(*out.device, *parsed.stream, replay_options);
    return out;
}

std::vector<std::string> scene_files() {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(kScenes))
        if (entry.path().extension() == ".sm2cs") files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

class Scene : public ::testing::TestWithParam<std::string> {};

// One thread on the reference paths (per-lane sampler and merger, the interpreter) against three
// threads on the block paths and the JIT: the bytes must depend on neither.
TEST_P(Scene, ReplaysCleanlyAndIdenticallyOnAnyThreadCountAndPath) {
    const Replayed one = replay_scene(GetParam(), 1, true);
    for (const auto& d : one.result.diagnostics) ADD_FAILURE() << d.to_string();
    ASSERT_FALSE(one.result.frames.empty()) << "the scene presents no frame";
    EXPECT_GT(one.result.statistics.pixels_shaded, 0u);
    const Replayed three = replay_scene(GetParam(), 3);
    ASSERT_EQ(one.images.size(), three.images.size());
    for (const auto& [name, surface] : one.images) {
        const auto it = three.images.find(name);
        ASSERT_NE(it, three.images.end()) << name;
        EXPECT_TRUE(surface.bytes() == it->second.bytes()) << name << " differs between 1 thread (reference paths, interpreter) and 3 threads (block paths, JIT)";
    }
    // The same counts: batches the fast paths skip unshaded (pixels_outside_texture) count as the
    // reference's shaded ones.
    const DrawStatistics& a = one.result.statistics;
    const DrawStatistics& b = three.result.statistics;
    EXPECT_EQ(a.pixels_rasterized, b.pixels_rasterized);
    EXPECT_EQ(a.pixels_shaded, b.pixels_shaded);
    EXPECT_EQ(a.pixels_killed, b.pixels_killed);
    EXPECT_EQ(a.pixels_written, b.pixels_written);
    EXPECT_EQ(a.pixels_outside_texture, 0u);
}

// Every image against its golden: 8-bit values equal within 1 step (libm may round a last bit
// differently on another machine), and the golden set must match the images the scene writes.
TEST_P(Scene, MatchesItsGoldenImages) {
    const std::string scene = GetParam().substr(0, GetParam().find('.'));
    const Replayed r = replay_scene(GetParam(), 2);
    const auto folder = kGoldens / scene;
    if (std::getenv("SM2_UPDATE_GOLDENS")) {
        std::filesystem::remove_all(folder);
        std::filesystem::create_directories(folder);
        for (const auto& [name, surface] : r.images) write_surface(surface, (folder / name).replace_extension(".png").string());
        GTEST_SKIP() << "goldens written to " << folder;
    }
    ASSERT_TRUE(std::filesystem::is_directory(folder)) << "no goldens for " << scene << " (SM2_UPDATE_GOLDENS=1)";
    size_t goldens = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) goldens += entry.path().extension() == ".png";
    EXPECT_EQ(goldens, r.images.size());
    for (const auto& [name, surface] : r.images) {
        const auto file = (folder / name).replace_extension(".png");
        ASSERT_TRUE(std::filesystem::exists(file)) << file;
        const std::string produced = (std::filesystem::path(testing::TempDir()) / (scene + "_" + name)).replace_extension(".png").string();
        write_surface(surface, produced);
        const ImageDifference d = compare_images(read_image(produced), read_image(file.string()), 1.0 / 255.0 + 1e-6);
        EXPECT_EQ(d.differing_pixels, 0u) << scene << "/" << name << ": max error " << d.max_abs_error * 255.0 << "/255";
        std::filesystem::remove(produced);
    }
}

INSTANTIATE_TEST_SUITE_P(Samples, Scene, ::testing::ValuesIn(scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param.substr(0, param.param.find('.'));
                             std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                             return name;
                         });

// probes.txt: `scene.sm2cs image x y RRGGBBAA tolerance # why`, one probe a line.
struct Probe {
    std::string scene, image;
    uint32_t x = 0, y = 0;
    uint32_t rgba = 0;
    int tolerance = 0;
    std::string why;
    int line = 0;
};

std::vector<Probe> read_probes() {
    std::vector<Probe> probes;
    std::ifstream in(kScenes / "probes.txt");
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto hash = line.find('#');
        const std::string why = hash == std::string::npos ? "" : line.substr(hash + 1);
        std::istringstream fields(line.substr(0, hash));
        Probe p;
        std::string color;
        if (!(fields >> p.scene)) continue;  // blank or comment line
        if (!(fields >> p.image >> p.x >> p.y >> color >> p.tolerance) || color.size() != 8) {
            ADD_FAILURE() << "probes.txt:" << number << ": malformed probe";
            continue;
        }
        p.rgba = static_cast<uint32_t>(std::stoul(color, nullptr, 16));
        p.why = why;
        p.line = number;
        probes.push_back(p);
    }
    return probes;
}

TEST(SceneProbes, EveryProbeHoldsItsHandDerivedColour) {
    const auto probes = read_probes();
    ASSERT_FALSE(probes.empty()) << "samples/scenes/probes.txt has no probes";
    std::map<std::string, Replayed> replays;
    for (const Probe& p : probes) {
        auto it = replays.find(p.scene);
        if (it == replays.end()) it = replays.emplace(p.scene, replay_scene(p.scene, 1)).first;
        const auto image = it->second.images.find(p.image);
        ASSERT_NE(image, it->second.images.end()) << "probes.txt:" << p.line << ": " << p.scene << " writes no " << p.image;
        const Surface& s = image->second;
        ASSERT_LT(p.x, s.width());
        ASSERT_LT(p.y, s.height());
        const Float4 v = s.read(p.x, p.y);
        const int expected[4] = {static_cast<int>(p.rgba >> 24), static_cast<int>(p.rgba >> 16 & 0xFF),
                                 static_cast<int>(p.rgba >> 8 & 0xFF), static_cast<int>(p.rgba & 0xFF)};
        for (unsigned c = 0; c < 4; ++c) {
            const int got = static_cast<int>(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f));
            EXPECT_LE(std::abs(got - expected[c]), p.tolerance)
                << "probes.txt:" << p.line << ": " << p.scene << " " << p.image << " (" << p.x << ", " << p.y
                << ") channel " << "RGBA"[c] << ": got " << got << ", expected " << expected[c] << " --" << p.why;
        }
    }
}

}  // namespace
}  // namespace sm2::runtime

namespace sm2::runtime {
namespace {

// Invariants a scene shows by construction, checked without any stored image.
// Scene 19 draws the same shadow volumes with two-sided stencil (left panel, x 0..255) and in
// two culled passes (middle panel, x 256..511): D3D9 defines both to leave the same stencil
// counts, so the two panels must be identical to the byte.
TEST(SceneInvariants, TwoSidedStencilEqualsTwoPasses) {
    const Replayed r = replay_scene("19_stencil_shadow_volumes.sm2cs", 1);
    const auto it = r.images.find("frame_0000.png");
    ASSERT_NE(it, r.images.end());
    const Surface& s = it->second;
    ASSERT_EQ(s.width(), 768u);
    size_t compared = 0;
    for (uint32_t y = 0; y < s.height(); ++y)
        for (uint32_t x = 0; x < 256; ++x) {
            ASSERT_EQ(s.read(x, y), s.read(x + 256, y)) << "(" << x << ", " << y << ")";
            ++compared;
        }
    EXPECT_EQ(compared, 256u * 256u);
}

// Scene 21 computes the log-average lightness of its HDR image on the GPU: log2(1e-4 + L) per
// texel (L = HSL lightness of the A16B16G16R16F texels) into a 64x64 R32F target, then three 4x4
// box passes down to 1x1. make_advanced_data.py computes the same average independently from
// the same texels in double precision: exp2(mean(log2(1e-4 + L))) = 0.147051.
TEST(SceneInvariants, HdrLogAverageMatchesAnIndependentComputation) {
    const Replayed r = replay_scene("21_hdr_tone_mapping.sm2cs", 1);
    ASSERT_TRUE(r.device);
    const Surface* lum1 = r.device->surface("lum1");
    ASSERT_NE(lum1, nullptr);
    ASSERT_EQ(lum1->width(), 1u);
    const double mean_log2 = lum1->read(0, 0)[0];
    EXPECT_NEAR(std::exp2(mean_log2), 0.147051, 2e-4);
}

}  // namespace
}  // namespace sm2::runtime
