#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a render: the first asks the render to
// stop and keep what it has; a second Ctrl-C ends the program at once.
namespace clpath {

class InterruptFlag {
public:
    InterruptFlag();   // installs the handlers
    ~InterruptFlag();  // restores the previous ones
    InterruptFlag(const InterruptFlag&) = delete;
    InterruptFlag& operator=(const InterruptFlag&) = delete;
    bool raised() const;
    int signal() const;  // the signal that raised it, 0 if none
};

}  // namespace clpath
