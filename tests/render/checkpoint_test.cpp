// Checkpoint files: what is written is read back exactly; anything else is refused by name.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "render/checkpoint.hpp"
#include "support/temp_paths.hpp"
#include "util/error.hpp"

namespace clpath {
namespace {

std::string temp_path(const std::string& name) {
    return test::temp_path("ckpt-" + name);
}

Checkpoint sample_checkpoint() {
    Checkpoint c;
    c.render_hash = 0x1234567890abcdefull;
    c.plan = {100, 8};
    c.done_chunks = {0, 2, 5};
    c.film = ExactFilm(3, 2);
    for (std::size_t i = 0; i < c.film.sums().size(); ++i) c.film.sums()[i] = (Fixed128(i) << 70) - 12345;
    c.film.set_samples_per_pixel(24);
    return c;
}

TEST(Checkpoint, RoundTripsExactly) {
    const std::string path = temp_path("roundtrip");
    const Checkpoint c = sample_checkpoint();
    write_checkpoint(path, c);
    const Checkpoint r = read_checkpoint(path);
    EXPECT_EQ(r.render_hash, c.render_hash);
    EXPECT_EQ(r.plan.total_samples, 100u);
    EXPECT_EQ(r.plan.chunk_samples, 8u);
    EXPECT_EQ(r.done_chunks, c.done_chunks);
    EXPECT_EQ(r.film.sums(), c.film.sums());
    EXPECT_EQ(r.film.samples_per_pixel(), 24u);
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
    std::filesystem::remove(path);
}

TEST(Checkpoint, AdaptiveRoundTripsWithHalfFilmAndCounts) {
    const std::string path = temp_path("adaptive");
    Checkpoint c = sample_checkpoint();
    c.noise_target = 0.02;
    c.film.half() = {Fixed128(1) << 80, -7, 3, 0, 99, Fixed128(5) << 64};
    c.film.set_pixel_samples({24, 8, 16, 24, 8, 8});
    write_checkpoint(path, c);
    const Checkpoint r = read_checkpoint(path);
    EXPECT_EQ(r.noise_target, 0.02);
    EXPECT_EQ(r.film.sums(), c.film.sums());
    EXPECT_EQ(r.film.half(), c.film.half());
    EXPECT_EQ(r.film.pixel_samples(), c.film.pixel_samples());
    // A count above the chunks' total is refused.
    c.film.set_pixel_samples({25, 8, 16, 24, 8, 8});
    write_checkpoint(path, c);
    EXPECT_THROW(read_checkpoint(path), Error);
    std::filesystem::remove(path);
}

TEST(Checkpoint, RefusesBrokenFiles) {
    const std::string path = temp_path("broken");
    write_checkpoint(path, sample_checkpoint());
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size - 1);
    EXPECT_THROW(read_checkpoint(path), Error);
    { std::ofstream(path, std::ios::binary) << "not a checkpoint at all, just text"; }
    try {
        read_checkpoint(path);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    }
    Checkpoint wrong = sample_checkpoint();
    wrong.film.set_samples_per_pixel(23);  // does not match its chunks
    write_checkpoint(path, wrong);
    EXPECT_THROW(read_checkpoint(path), Error);
    std::filesystem::remove(path);
    EXPECT_THROW(read_checkpoint(path), Error);  // missing
}

std::string message_of(const std::string& path) {
    try {
        read_checkpoint(path);
    } catch (const CheckpointError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected a CheckpointError for " << path;
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The checkpoint's bytes, one bit flipped at `offset` (counted from the end when negative).
void flip_bit(const std::string& path, long long offset) {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    const auto size = (long long)std::filesystem::file_size(path);
    f.seekg(offset < 0 ? size + offset : offset);
    char c;
    f.get(c);
    f.seekp(offset < 0 ? size + offset : offset);
    f.put(char(c ^ 0x10));
}

TEST(Checkpoint, ChecksumCatchesAFlippedBit) {
    const std::string path = temp_path("flipped");
    // One bit in the sums, in the chunk list, in the header's render hash, in the checksum itself.
    const long long header = 64, sums_end = -8;
    for (long long offset : {sums_end - 20, header + 4, 8LL, -3LL}) {
        write_checkpoint(path, sample_checkpoint());
        flip_bit(path, offset);
        const std::string e = message_of(path);
        EXPECT_TRUE(has(e, path + ": the checkpoint is damaged: its xxHash checksum does not match its contents")) << offset << ": " << e;
    }
    // Control: the file as written reads back.
    write_checkpoint(path, sample_checkpoint());
    EXPECT_EQ(read_checkpoint(path).film.sums(), sample_checkpoint().film.sums());
    std::filesystem::remove(path);
}

TEST(Checkpoint, ForgedHeaderIsRefusedBeforeAllocating) {
    // A header claiming a 16384 x 16384 image (12 GiB of sums) and 2^32 chunks
    // (32 GiB of chunk list) in a file of a few hundred bytes. With the address
    // space capped well below that, an allocation before the size check would
    // throw std::bad_alloc instead of the message.
    const std::string path = temp_path("forged");
    write_checkpoint(path, sample_checkpoint());
    {
        std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
        const std::uint64_t side = 16384, chunks = 1ull << 32;
        f.seekp(40);  // width, height, then the chunk count
        f.write(reinterpret_cast<const char*>(&side), 8);
        f.write(reinterpret_cast<const char*>(&side), 8);
        f.write(reinterpret_cast<const char*>(&chunks), 8);
    }
    rlimit old{};
    ASSERT_EQ(getrlimit(RLIMIT_AS, &old), 0);
    rlimit capped = old;
    capped.rlim_cur = rlim_t(4) << 30;  // 4 GiB: the test's own needs and none of the forged ones
    ASSERT_EQ(setrlimit(RLIMIT_AS, &capped), 0);
    std::string e;
    try {
        read_checkpoint(path);
    } catch (const CheckpointError& x) {
        e = x.what();
    } catch (const std::bad_alloc&) {
        e = "std::bad_alloc: the header was trusted";
    }
    setrlimit(RLIMIT_AS, &old);
    EXPECT_TRUE(has(e, path + ": the checkpoint's header describes 47244640328 bytes, but the file has ")) << e;
    std::filesystem::remove(path);
}

TEST(Checkpoint, SizeAndFormatAreChecked) {
    const std::string path = temp_path("size");
    write_checkpoint(path, sample_checkpoint());
    { std::ofstream(path, std::ios::binary | std::ios::app) << "x"; }
    EXPECT_TRUE(has(message_of(path), "but the file has ")) << message_of(path);
    write_checkpoint(path, sample_checkpoint());
    std::filesystem::resize_file(path, std::filesystem::file_size(path) - 8);  // the checksum cut off
    EXPECT_TRUE(has(message_of(path), "but the file has ")) << message_of(path);
    // A format-1 file (written before checkpoints had a checksum) is named as such.
    write_checkpoint(path, sample_checkpoint());
    {
        std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
        f.seekp(7);
        f.put('1');
    }
    EXPECT_TRUE(has(message_of(path), "a checkpoint of an older clpath (format 1, without a checksum)")) << message_of(path);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace clpath
