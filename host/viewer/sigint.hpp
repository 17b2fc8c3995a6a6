#pragma once
// Ctrl-C ends the viewer's loop instead of killing it, so the window, GL and
// OpenCL are torn down in order and the exit status is clean.
namespace clpath::viewer {

// Installs the handler for its lifetime; the previous one comes back after.
class SigintFlag {
public:
    SigintFlag();
    ~SigintFlag();
    SigintFlag(const SigintFlag&) = delete;
    SigintFlag& operator=(const SigintFlag&) = delete;
    bool raised() const;
};

}  // namespace clpath::viewer
