#pragma once
// Ctrl-C (SIGINT) and SIGTERM during a render: the first asks the render loop
// to stop after the pass it is in, so that what it has can be written; a
// second one ends the program at once, as usual.
namespace clpath {

// Installs the handlers for the lifetime of the object; the destructor puts
// the previous ones back.
class InterruptGuard {
public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;
    // The signal that asked to stop (SIGINT or SIGTERM), or 0.
    static int requested();
};

}  // namespace clpath
