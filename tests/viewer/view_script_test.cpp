// The viewer's script language and its frame-by-frame runner, and the keymap it shares with the keyboard.
#include <gtest/gtest.h>

#include <algorithm>

#include "shared_structs.h"
#include "util/error.hpp"
#include "viewer/keymap.hpp"
#include "viewer/view_script.hpp"

using namespace clpath;
using namespace clpath::viewer;
using K = ScriptCommand::Kind;

namespace {

std::string error_of(const std::string& text) {
    try {
        parse_view_script(text, "s.txt");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ViewerScript, ParsesEveryCommandWithComments) {
    const auto cmds = parse_view_script(
        "# a comment\n\nwait 3\nwait-spp 16  # trailing\nkey 4\nhold w 5\ndrag 10 -2.5\nscroll -1\n"
        "screenshot\nscreenshot named\ncapture out/x.png\nresize 320 200\ncamera\nquit\n",
        "s.txt");
    ASSERT_EQ(cmds.size(), 12u);
    EXPECT_EQ(cmds[0].kind, K::Wait);
    EXPECT_EQ(cmds[0].a, 3);
    EXPECT_EQ(cmds[0].line, 3);
    EXPECT_EQ(cmds[1].kind, K::WaitSpp);
    EXPECT_EQ(cmds[2].text, "4");
    EXPECT_EQ(cmds[3].kind, K::Hold);
    EXPECT_EQ(cmds[3].text, "w");
    EXPECT_EQ(cmds[3].a, 5);
    EXPECT_EQ(cmds[4].b, -2.5);
    EXPECT_EQ(cmds[6].text, "");
    EXPECT_EQ(cmds[7].text, "named");
    EXPECT_EQ(cmds[8].text, "out/x.png");
    EXPECT_EQ(cmds[9].kind, K::Resize);
    EXPECT_EQ(cmds[11].kind, K::Quit);
}

TEST(ViewerScript, ClickTakesAWindowPixel) {
    const auto cmds = parse_view_script("click 12 30.5\n", "s.txt");
    ASSERT_EQ(cmds.size(), 1u);
    EXPECT_EQ(cmds[0].kind, K::Click);
    EXPECT_EQ(cmds[0].a, 12);
    EXPECT_EQ(cmds[0].b, 30.5);
    EXPECT_NE(error_of("click 3\n").find("s.txt:1: 'click' needs 2 number(s)"), std::string::npos);
    EXPECT_NE(error_of("click -1 4\n").find("s.txt:1: a click needs a window pixel"), std::string::npos);
}

TEST(ViewerScript, ErrorsNameTheLine) {
    EXPECT_NE(error_of("wait 1\njump\n").find("s.txt:2: unknown command 'jump'"), std::string::npos);
    EXPECT_NE(error_of("key\n").find("s.txt:1: 'key' needs an argument"), std::string::npos);
    EXPECT_NE(error_of("key x\n").find("unknown key 'x'"), std::string::npos);
    EXPECT_NE(error_of("drag 1\n").find("'drag' needs 2 number(s)"), std::string::npos);
    EXPECT_NE(error_of("wait many\n").find("'wait' needs 1 number(s)"), std::string::npos);
    EXPECT_NE(error_of("quit now\n").find("unexpected 'now'"), std::string::npos);
    EXPECT_NE(error_of("wait -1\n").find("zero or more"), std::string::npos);
    EXPECT_THROW(load_view_script("/no/such/script.txt"), Error);
}

TEST(ViewerScript, RunnerWaitsFramesAndSamples) {
    ScriptRunner r(parse_view_script("key 1\nwait 2\nkey 2\nwait-spp 10\nkey 3\n", "s"));
    auto s = r.next_frame(0);
    ASSERT_EQ(s.commands.size(), 1u);  // key 1, then the wait starts
    EXPECT_EQ(s.commands[0].text, "1");
    EXPECT_TRUE(r.next_frame(0).commands.empty());  // second waited frame
    s = r.next_frame(0);
    ASSERT_EQ(s.commands.size(), 1u);
    EXPECT_EQ(s.commands[0].text, "2");
    EXPECT_TRUE(r.next_frame(9).commands.empty());
    s = r.next_frame(10);
    ASSERT_EQ(s.commands.size(), 1u);
    EXPECT_EQ(s.commands[0].text, "3");
    EXPECT_TRUE(r.finished());
}

TEST(ViewerScript, HoldKeepsAKeyDownForItsFramesAndBlocks) {
    ScriptRunner r(parse_view_script("hold w 3\nkey 4\n", "s"));
    for (int i = 0; i < 3; ++i) {
        const auto s = r.next_frame(0);
        ASSERT_EQ(s.held, std::vector<std::string>{"w"}) << "frame " << i;
        EXPECT_TRUE(s.commands.empty());
    }
    const auto s = r.next_frame(0);
    EXPECT_TRUE(s.held.empty());
    ASSERT_EQ(s.commands.size(), 1u);
    EXPECT_TRUE(r.finished());
}

TEST(ViewerScript, CaptureEndsTheFramesCommands) {
    ScriptRunner r(parse_view_script("capture a.png\nkey 4\n", "s"));
    EXPECT_EQ(r.next_frame(0).commands.size(), 1u);
    EXPECT_FALSE(r.finished());
    EXPECT_EQ(r.next_frame(0).commands.at(0).text, "4");
}

TEST(ViewerScript, WaitDenoisedWaitsForTheShownImageToCatchUp) {
    const auto cmds = parse_view_script("wait-denoised\nkey 1\n", "s");
    ASSERT_EQ(cmds.size(), 2u);
    EXPECT_EQ(cmds[0].kind, K::WaitDenoised);
    EXPECT_NE(error_of("wait-denoised 3\n").find("unexpected '3'"), std::string::npos);
    ScriptRunner r(cmds);
    EXPECT_TRUE(r.next_frame(4, false).commands.empty());
    EXPECT_TRUE(r.next_frame(5, false).commands.empty());
    EXPECT_EQ(r.next_frame(5, true).commands.at(0).text, "1");
    EXPECT_TRUE(r.finished());
    // Scripts without the argument (denoising off) never wait.
    ScriptRunner off(parse_view_script("wait-denoised\nkey 2\n", "s"));
    EXPECT_EQ(off.next_frame(0).commands.at(0).text, "2");
    // A key before it in the same frame may turn denoising on: it waits for the next frame's answer.
    ScriptRunner keyed(parse_view_script("key n\nwait-denoised\nkey 3\n", "s"));
    EXPECT_EQ(keyed.next_frame(0, true).commands.size(), 1u);
    EXPECT_TRUE(keyed.next_frame(1, false).commands.empty());
    EXPECT_EQ(keyed.next_frame(1, true).commands.at(0).text, "3");
}

TEST(ViewerKeymap, NumberKeysChooseEveryIntegratorOnce) {
    std::vector<unsigned> seen;
    for (char k = '1'; k <= '7'; ++k) {
        const auto a = action_for_key(std::string(1, k));
        ASSERT_TRUE(a && a->action == Action::SetIntegrator) << k;
        seen.push_back(a->arg);
    }
    std::sort(seen.begin(), seen.end());
    EXPECT_EQ(std::unique(seen.begin(), seen.end()), seen.end());
    EXPECT_EQ(seen.back(), CLP_INTEGRATOR_COUNT - 1);
    EXPECT_FALSE(action_for_key("w"));
    EXPECT_TRUE(is_movement_key("w"));
    EXPECT_EQ(action_for_key("b")->action, Action::ToggleBvhOverlay);
    EXPECT_EQ(action_for_key("n")->action, Action::ToggleDenoise);
}
