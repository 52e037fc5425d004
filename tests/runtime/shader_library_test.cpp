// Shader loading: #include expansion with #line mapping, and errors that name file and line.

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "temp_dir.hpp"

namespace {

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

std::string message_of(const std::function<void()>& action) {
    try {
        action();
    } catch (const luxel::ShaderError& e) {
        return e.what();
    }
    return "(no ShaderError thrown)";
}

class ShaderLibraryTest : public ::testing::Test {
  protected:
    luxel::testing::TempDir dir{"luxel-shaders"};
    luxel::ShaderLibrary library{{dir.path()}};
};

TEST_F(ShaderLibraryTest, IncludesAreExpandedOnceWithLineDirectives) {
    write_file(dir / "lib/a.glsl", "#include \"b.glsl\"\nfloat a() { return b(); }\n");
    write_file(dir / "lib/b.glsl", "float b() { return 1.0; }\n");
    write_file(dir / "main.frag",
               "#version 450 core\n#include \"lib/a.glsl\"\n#include \"lib/b.glsl\"\nvoid "
               "main() {}\n");
    const auto shader = library.preprocess("main.frag", "#define K 3");
    ASSERT_EQ(shader.files.size(), 3u);
    EXPECT_EQ(shader.files[0].filename(), "main.frag");
    EXPECT_EQ(shader.files[1].filename(), "a.glsl");
    EXPECT_EQ(shader.files[2].filename(), "b.glsl");
    const std::string& text = shader.text;
    // #version first, then the defines, then the line mapping back to main.frag line 2.
    EXPECT_EQ(text.rfind("#version 450 core\n#define K 3\n#line 2 0\n", 0), 0u) << text;
    // b.glsl appears once even though it is included twice.
    const auto first = text.find("float b()");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(text.find("float b()", first + 1), std::string::npos) << text;
    EXPECT_NE(text.find("#line 1 2\nfloat b()"), std::string::npos) << text;
    EXPECT_NE(text.find("#line 2 1\nfloat a()"), std::string::npos) << text;
    EXPECT_NE(text.find("#line 4 0\nvoid main()"), std::string::npos) << text;
}

TEST_F(ShaderLibraryTest, MissingFileNamesThePathsTried) {
    const std::string message = message_of([&] { (void)library.resolve("nowhere.frag"); });
    EXPECT_NE(message.find("nowhere.frag"), std::string::npos) << message;
    EXPECT_NE(message.find((dir / "nowhere.frag").string()), std::string::npos) << message;
}

TEST_F(ShaderLibraryTest, MissingIncludeNamesTheIncludingFileAndLine) {
    write_file(dir / "main.frag", "#version 450 core\n\n#include \"gone.glsl\"\n");
    const std::string message = message_of([&] { (void)library.preprocess("main.frag"); });
    EXPECT_NE(message.find("main.frag:3"), std::string::npos) << message;
    EXPECT_NE(message.find("gone.glsl"), std::string::npos) << message;
}

TEST_F(ShaderLibraryTest, IncludeCycleIsAnError) {
    write_file(dir / "a.glsl", "#include \"b.glsl\"\n");
    write_file(dir / "b.glsl", "#include \"a.glsl\"\n");
    write_file(dir / "main.frag", "#version 450 core\n#include \"a.glsl\"\n");
    const std::string message = message_of([&] { (void)library.preprocess("main.frag"); });
    EXPECT_NE(message.find("cycle"), std::string::npos) << message;
    EXPECT_NE(message.find("b.glsl:1"), std::string::npos) << message;
}

TEST_F(ShaderLibraryTest, MalformedIncludeIsAnError) {
    write_file(dir / "main.frag", "#version 450 core\n#include <system.glsl>\n");
    const std::string message = message_of([&] { (void)library.preprocess("main.frag"); });
    EXPECT_NE(message.find("main.frag:2"), std::string::npos) << message;
}

TEST(ShaderLogMapping, DriverFormatsMapToFileAndLine) {
    const std::vector<std::filesystem::path> files = {"shaders/main.frag", "shaders/inc.glsl"};
    EXPECT_EQ(luxel::map_shader_log("0:12(3): error: syntax error", files),
              "shaders/main.frag:12:3: error: syntax error\n");
    EXPECT_EQ(luxel::map_shader_log("1(7) : error C0000: bad token", files),
              "shaders/inc.glsl:7: error C0000: bad token\n");
    EXPECT_EQ(luxel::map_shader_log("ERROR: 1:4: 'x' : undeclared", files),
              "shaders/inc.glsl:4: error: 'x' : undeclared\n");
    EXPECT_EQ(luxel::map_shader_log("9:1(1): error: out of range", files),
              "<source 9>:1:1: error: out of range\n");
}

class ShaderCompileTest : public ShaderLibraryTest {
  protected:
    void SetUp() override {
        luxel::GlContextOptions options;
        options.backend = luxel::GlBackend::Egl;
        context = luxel::create_gl_context(options);
    }
    std::unique_ptr<luxel::GlContext> context;
};

TEST_F(ShaderCompileTest, SyntaxErrorNamesFileAndLine) {
    write_file(
        dir / "bad.frag",
        "#version 450 core\nout vec4 colour;\nvoid main() {\n    colour = vec4(1.0) + ;\n}\n");
    write_file(dir / "ok.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n");
    const std::string message = message_of([&] {
        (void)library.build(
            {{luxel::ShaderStage::Vertex, "ok.vert"}, {luxel::ShaderStage::Fragment, "bad.frag"}});
    });
    EXPECT_NE(message.find((dir / "bad.frag").string() + ":4:"), std::string::npos) << message;
    EXPECT_NE(message.find("error"), std::string::npos) << message;
}

TEST_F(ShaderCompileTest, ErrorInIncludedFileNamesThatFile) {
    write_file(dir / "inc/helpers.glsl", "float helper() {\n    return undefined_name;\n}\n");
    write_file(dir / "main.frag",
               "#version 450 core\n#include \"inc/helpers.glsl\"\nout vec4 c;\nvoid main() { c "
               "= vec4(helper()); }\n");
    write_file(dir / "ok.vert", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n");
    const std::string message = message_of([&] {
        (void)library.build(
            {{luxel::ShaderStage::Vertex, "ok.vert"}, {luxel::ShaderStage::Fragment, "main.frag"}});
    });
    EXPECT_NE(message.find("helpers.glsl:2"), std::string::npos) << message;
}

TEST_F(ShaderCompileTest, LinkErrorNamesThePrograms) {
    write_file(dir / "a.vert",
               "#version 450 core\nout vec3 v_only_here;\nvoid main() { "
               "v_only_here = vec3(1.0); gl_Position = vec4(0.0); }\n");
    write_file(dir / "a.frag",
               "#version 450 core\nin vec4 v_missing;\nout vec4 c;\nvoid main() { c = "
               "v_missing; }\n");
    const std::string message = message_of([&] {
        (void)library.build(
            {{luxel::ShaderStage::Vertex, "a.vert"}, {luxel::ShaderStage::Fragment, "a.frag"}});
    });
    EXPECT_NE(message.find("a.vert + a.frag"), std::string::npos) << message;
}

TEST_F(ShaderCompileTest, ProjectShadersCompile) {
    const luxel::ShaderLibrary project;
    EXPECT_NO_THROW((void)project.build({{luxel::ShaderStage::Vertex, "test_scene/lit.vert"},
                                         {luxel::ShaderStage::Fragment, "test_scene/lit.frag"}}));
    EXPECT_NO_THROW((void)project.build({{luxel::ShaderStage::Vertex, "post/fullscreen.vert"},
                                         {luxel::ShaderStage::Fragment, "post/tone_map.frag"}}));
}

}  // namespace
