#include "viewer/sigint.hpp"

#include <csignal>

namespace clpath::viewer {
namespace {

volatile std::sig_atomic_t g_raised = 0;
void on_sigint(int) { g_raised = 1; }
void (*g_previous)(int) = SIG_DFL;

}  // namespace

SigintFlag::SigintFlag() {
    g_raised = 0;
    g_previous = std::signal(SIGINT, on_sigint);
    if (g_previous == SIG_ERR) g_previous = SIG_DFL;
}

SigintFlag::~SigintFlag() { std::signal(SIGINT, g_previous); }

bool SigintFlag::raised() const { return g_raised != 0; }

}  // namespace clpath::viewer
