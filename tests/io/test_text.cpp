// util/text: the one copy of joining, quoting (messages, shells, CSV), did-you-mean and JSON
// files read with the limits every input gets.
#include "../support/error_text.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <pathlet/scene.hpp>

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {

// What /bin/sh makes of a command line: each argument on its own line.
std::vector<std::string> shell_words(const std::string& command_line) {
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / ("shell_words_" + std::to_string(::getpid()) + ".txt");
    const std::string cmd = "printf '%s\\n' " + command_line + " > " + out.string();
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(out);
    std::vector<std::string> words;
    for (std::string w; std::getline(in, w);) words.push_back(w);
    fs::remove(out);
    return words;
}

fs::path scratch_file(const std::string& name, const std::string& bytes) {
    const fs::path p = fs::path(PATHLET_TEST_BINARY_DIR) / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
}

std::string data_error(const std::function<void()>& f) { return test::error_text<DataError>(f); }

}  // namespace

TEST(Text, JoinAndSplit) {
    EXPECT_EQ(text::join({"a", "b", "c"}), "a, b, c");
    EXPECT_EQ(text::join({"a", "b"}, "|"), "a|b");
    EXPECT_EQ(text::join({}), "");
    EXPECT_EQ(text::split("isl,,variant1_lineao,", ','), (std::vector<std::string>{"isl", "variant1_lineao"}));
}

TEST(Text, ShellQuotingSurvivesAShellWhateverTheArgumentHolds) {
    // One of the three former copies wrapped arguments in '...' without escaping a quote inside.
    const std::vector<std::string> words = {"pathlet", "render", "it's here.json", "--set", "label=say \"hi\"",
                                            "$HOME", "a;b", "`x`", "tab\there", "", "back\\slash", "plain-1.5_x/y:z"};
    EXPECT_EQ(shell_words(text::shell_command(words)), words);
    EXPECT_EQ(text::shell_quote("plain-1.5_x/y:z"), "plain-1.5_x/y:z") << "plain words stay readable";
    EXPECT_EQ(text::shell_quote("it's"), "'it'\\''s'");
    EXPECT_EQ(text::shell_quote(""), "''");
}

TEST(Text, CsvFieldsFollowRfc4180) {
    EXPECT_EQ(text::csv_field("plain"), "plain");
    EXPECT_EQ(text::csv_field("a,b"), "\"a,b\"");
    EXPECT_EQ(text::csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(text::csv_field("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(text::csv_field("cr\r"), "\"cr\r\"");
}

TEST(Text, DidYouMeanQuotesThePrefixedCandidate) {
    EXPECT_EQ(text::did_you_mean("widnow", {"window", "samples"}, "$"), " (did you mean '$window'?)");
    EXPECT_EQ(text::did_you_mean("zzz", {"window"}), "");
    EXPECT_EQ(text::pointer_escape("a/b~c"), "a~1b~0c");
}

TEST(Text, JsonFilesGiveFileLineAndColumn) {
    const fs::path bad = scratch_file("text_bad.json", "{\n  \"a\": [1,\n  ]\n}");
    const std::string e = data_error([&] { text::read_json_file(bad.string(), "test file"); });
    EXPECT_EQ(e.rfind(bad.string() + ":3:3: not valid JSON (test file): syntax error", 0), 0u) << e;
    const fs::path comments = scratch_file("text_comments.json", "// a comment\n{\"a\": 1 /* and another */}");
    EXPECT_EQ(text::read_json_file(comments.string(), "test file")["a"], 1);
    const fs::path big_number = scratch_file("text_big.json", "{\"a\": 1e400}");
    EXPECT_NE(data_error([&] { text::read_json_file(big_number.string(), "x"); }).find("number out of range: '1e400'"),
              std::string::npos);
    EXPECT_NE(data_error([&] { text::read_json_file("/no/such/file.json", "the experiment file"); })
                  .find("/no/such/file.json: cannot open the experiment file"),
              std::string::npos);
    EXPECT_NE(data_error([&] { text::read_json_file(PATHLET_TEST_BINARY_DIR, "x"); }).find("is a directory"),
              std::string::npos);
}

TEST(Text, JsonFilesHaveTheLimitsOfGraphFiles) {
    const fs::path deep = scratch_file("text_deep.json", std::string(100000, '[') + std::string(100000, ']'));
    const std::string e = data_error([&] { text::read_json_file(deep.string(), "x"); });
    EXPECT_NE(e.find(deep.string() + ":1:129: not valid JSON (x): nesting deeper than 128"), std::string::npos) << e;
    // Size: a file beyond PATHLET_MAX_JSON_BYTES is refused before it is parsed.
    const fs::path big = scratch_file("text_big_file.json", "[" + std::string(10000, ' ') + "]");
    ::setenv("PATHLET_MAX_JSON_BYTES", "4096", 1);
    const std::string too_big = data_error([&] { text::read_json_file(big.string(), "the view script"); });
    ::unsetenv("PATHLET_MAX_JSON_BYTES");
    EXPECT_NE(too_big.find(big.string() + ": the view script is larger than"), std::string::npos) << too_big;
    EXPECT_TRUE(text::read_json_file(big.string(), "x").is_array());
}
