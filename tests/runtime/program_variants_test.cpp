// ProgramVariants: one program per set of compile-time features, built once, with the features'
// code compiled in or out; and every variant of the project's switched shaders compiles.

#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/program_variants.hpp"
#include "temp_dir.hpp"

namespace {

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

class ProgramVariantsTest : public ::testing::Test {
  protected:
    void SetUp() override {
        luxel::GlContextOptions options;
        options.backend = luxel::GlBackend::Egl;
        context = luxel::create_gl_context(options);
        write_file(dir / "v.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n");
        // RED picks which uniform the shader reads; the other is compiled out (location -1).
        write_file(dir / "f.frag",
                   "#version 450 core\n#ifndef RED\n#define RED 1\n#endif\n"
                   "uniform float u_red;\nuniform float u_green;\nuniform float u_scale;\n"
                   "out vec4 c;\nvoid main() {\n#if RED\n    c = vec4(u_red, 0.0, 0.0, 1.0);\n"
                   "#else\n    c = vec4(0.0, u_green, 0.0, 1.0);\n#endif\n"
                   "#if BRIGHT\n    c *= u_scale;\n#endif\n}\n");
    }
    luxel::testing::TempDir dir{"luxel-variants"};
    luxel::ShaderLibrary library{{dir.path()}};
    std::unique_ptr<luxel::GlContext> context;
};

TEST_F(ProgramVariantsTest, EachSetOfFeaturesIsBuiltOnceWithItsCodeOnly) {
    luxel::ProgramVariants variants(library, "v.vert", "f.frag", {"RED", "BRIGHT"},
                                    "#define UNUSED 7\n");
    EXPECT_EQ(variants.defines_for(0b01), "#define UNUSED 7\n#define RED 1\n#define BRIGHT 0\n");
    EXPECT_EQ(variants.built(), 0u) << "nothing is built before it is asked for";

    const GLuint red = variants.get(0b01).id();
    EXPECT_GE(variants.get(0b01).uniform_location("u_red"), 0);
    EXPECT_EQ(variants.get(0b01).uniform_location("u_green"), -1);
    EXPECT_EQ(variants.get(0b01).uniform_location("u_scale"), -1);

    const GLuint green_bright = variants.get(0b10).id();
    EXPECT_EQ(variants.get(0b10).uniform_location("u_red"), -1);
    EXPECT_GE(variants.get(0b10).uniform_location("u_green"), 0);
    EXPECT_GE(variants.get(0b10).uniform_location("u_scale"), 0);

    EXPECT_NE(red, green_bright);
    EXPECT_EQ(variants.get(0b01).id(), red) << "asked again, the same program";
    EXPECT_EQ(variants.get(0b101).id(), red) << "a bit past the features names nothing";
    EXPECT_EQ(variants.built(), 2u);
}

TEST_F(ProgramVariantsTest, ABrokenVariantFailsWhenItIsAskedForAndNamesItsFile) {
    write_file(dir / "g.frag",
               "#version 450 core\nout vec4 c;\nvoid main() {\n#if BROKEN\n    c = ;\n#else\n"
               "    c = vec4(1.0);\n#endif\n}\n");
    luxel::ProgramVariants variants(library, "v.vert", "g.frag", {"BROKEN"});
    EXPECT_NO_THROW((void)variants.get(0));
    try {
        (void)variants.get(1);
        FAIL() << "the broken variant compiled";
    } catch (const luxel::ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find("g.frag:5"), std::string::npos) << e.what();
    }
    EXPECT_EQ(variants.built(), 1u);
}

// Every variant the renderer may ask for compiles and links, so a feature a test scene never
// turns on cannot hide a broken #if block until a level needs it.
TEST_F(ProgramVariantsTest, EveryVariantOfTheProjectsSwitchedShadersCompiles) {
    const luxel::ShaderLibrary project;
    struct Switched {
        const char* fragment;
        std::vector<std::string> features;
        const char* defines;
    };
    const Switched switched[] = {
        {"render/indirect.frag", {"IIM_BICUBIC", "PROBES"}, ""},
        {"render/composite.frag", {"CAUSTIC_LAYER", "SKY", "SKY_MASK"}, ""},
        {"render/direct.frag", {"CUBE_SHADOWS", "MAP_SHADOWS"}, "#define LIGHTS_PER_BATCH 4\n"},
    };
    for (const Switched& one : switched) {
        luxel::ProgramVariants variants(project, "post/fullscreen.vert", one.fragment, one.features,
                                        one.defines);
        const std::uint32_t count = 1u << one.features.size();
        for (std::uint32_t mask = 0; mask < count; ++mask) {
            EXPECT_NO_THROW((void)variants.get(mask)) << one.fragment << " variant " << mask;
        }
        EXPECT_EQ(variants.built(), count) << one.fragment;
    }
}

}  // namespace
