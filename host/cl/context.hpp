#pragma once
// The OpenCL runtime layer: one Context owns the device's context and queue
// and every buffer made through it; each call is checked and errors carry names.
#include <CL/cl.h>

#include <atomic>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cl/device.hpp"
#include "cl/errors.hpp"

namespace clpath {

// The bytes a Context has allocated and not yet freed. Shared with its buffers
// (so a buffer that outlives its Context still gives back to a live counter),
// atomic because a buffer may be freed on another thread than its Context's.
using MemoryCounter = std::atomic<std::size_t>;

// Move-only owner of one cl_mem. A buffer made by Context::buffer gives its
// bytes back to that Context's counter when it is freed; one wrapping memory
// the Context did not allocate (an OpenGL buffer) counts nothing.
class Buffer {
public:
    Buffer() = default;
    Buffer(cl_mem m, std::size_t bytes) : mem_(m), bytes_(bytes) {}
    Buffer(cl_mem m, std::size_t bytes, std::shared_ptr<MemoryCounter> counter)
        : mem_(m), bytes_(bytes), counter_(std::move(counter)) {}
    Buffer(Buffer&& o) noexcept
        : mem_(std::exchange(o.mem_, nullptr)), bytes_(std::exchange(o.bytes_, 0)), counter_(std::move(o.counter_)) {}
    Buffer& operator=(Buffer&& o) noexcept {
        if (this != &o) {
            release();
            mem_ = std::exchange(o.mem_, nullptr);
            bytes_ = std::exchange(o.bytes_, 0);
            counter_ = std::move(o.counter_);
        }
        return *this;
    }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    ~Buffer() { release(); }
    cl_mem get() const { return mem_; }
    std::size_t bytes() const { return bytes_; }

private:
    void release() noexcept {
        if (mem_) clReleaseMemObject(mem_);
        if (counter_) *counter_ -= bytes_;
        mem_ = nullptr;
        bytes_ = 0;
        counter_.reset();
    }

    cl_mem mem_ = nullptr;
    std::size_t bytes_ = 0;
    std::shared_ptr<MemoryCounter> counter_;
};

// Move-only owner of one cl_kernel, with typed argument setting.
class Kernel {
public:
    Kernel() = default;
    Kernel(cl_kernel k, std::string name) : k_(k), name_(std::move(name)) {}
    Kernel(Kernel&& o) noexcept : k_(std::exchange(o.k_, nullptr)), name_(std::move(o.name_)) {}
    Kernel& operator=(Kernel&& o) noexcept {
        std::swap(k_, o.k_);
        std::swap(name_, o.name_);
        return *this;
    }
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;
    ~Kernel() {
        if (k_) clReleaseKernel(k_);
    }
    template <class T>
    Kernel& arg(cl_uint i, const T& v) {
        cl_check(clSetKernelArg(k_, i, sizeof(T), &v), "clSetKernelArg(" + name_ + ", " + std::to_string(i) + ")");
        return *this;
    }
    Kernel& arg(cl_uint i, const Buffer& b) {
        cl_mem m = b.get();
        return arg(i, m);
    }
    cl_kernel get() const { return k_; }
    const std::string& name() const { return name_; }

private:
    cl_kernel k_ = nullptr;
    std::string name_;
};

class Context {
public:
    explicit Context(const DeviceInfo& device);
    // With context properties (zero-terminated), e.g. to share with OpenGL (cl/gl_sharing.hpp).
    Context(const DeviceInfo& device, const std::vector<cl_context_properties>& properties);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device() const { return device_; }
    cl_context get() const { return ctx_; }
    cl_command_queue queue() const { return queue_; }

    // Allocates after checking the size against the device's largest single
    // allocation and against its global memory, so that a scene too large for
    // the device gives a clear message rather than a failed launch later.
    // what names the buffer in that message.
    Buffer buffer(std::size_t bytes, cl_mem_flags flags, const std::string& what, const void* init = nullptr);

    // The check alone, for callers that want to fail before building anything.
    void check_fits(const std::vector<std::pair<std::string, std::size_t>>& buffers) const;

    void write(const Buffer& b, const void* data, std::size_t bytes, std::size_t offset = 0);
    void read(const Buffer& b, void* data, std::size_t bytes, std::size_t offset = 0);
    // The same, enqueued without waiting: data must stay as it is (write) or
    // untouched (read) until the returned event completes; the caller
    // releases the event (nullptr when not asked for).
    cl_event write_async(const Buffer& b, const void* data, std::size_t bytes, bool want_event = false);
    cl_event read_async(const Buffer& b, void* data, std::size_t bytes, bool want_event = false);
    // Sets every 4-byte word of b (whose size is a multiple of 4) to word, without waiting.
    void fill_async(const Buffer& b, cl_uint word);
    // Sets every byte of b to zero (blocking).
    void zero(const Buffer& b);
    template <class T>
    void write(const Buffer& b, const std::vector<T>& v) { write(b, v.data(), v.size() * sizeof(T)); }
    template <class T>
    void read(const Buffer& b, std::vector<T>& v) { read(b, v.data(), v.size() * sizeof(T)); }

    // A kernel from a program built for this context (see program.hpp).
    Kernel kernel(cl_program program, const std::string& name);

    // Enqueues a 1-D launch; local 0 lets the driver choose. Returns the event
    // when want_event is set (the queue profiles, so its times are kernel times).
    cl_event launch(const Kernel& k, std::size_t global, std::size_t local = 0, bool want_event = false);
    void finish();

    // Bytes of the buffers made by this Context that are still alive.
    std::size_t allocated_bytes() const { return *allocated_; }
    // Bytes moved between host and device so far (uploads at creation included).
    std::uint64_t bytes_to_device() const { return to_device_; }
    std::uint64_t bytes_from_device() const { return from_device_; }

private:
    DeviceInfo device_;
    cl_context ctx_ = nullptr;
    cl_command_queue queue_ = nullptr;
    std::shared_ptr<MemoryCounter> allocated_ = std::make_shared<MemoryCounter>(0);
    std::atomic<std::uint64_t> to_device_{0}, from_device_{0};
    bool huge_pages_ = true;  // CLPATH_HUGE_PAGES (cl/huge_pages.hpp): large read-only buffers read in place
};

// Seconds a finished, profiled event spent executing; releases the event.
double event_seconds(cl_event e);
// Seconds from the start of `first` to the end of `last` (profiled events of
// one in-order queue); waits for last and releases both.
double event_span_seconds(cl_event first, cl_event last);

}  // namespace clpath
