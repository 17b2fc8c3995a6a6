// Checkpoint files: what is written is read back exactly; anything else is refused by name.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace clpath
