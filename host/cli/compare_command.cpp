// clpath compare A B: how far image A is from reference B.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/option_checks.hpp"
#include "image/compare.hpp"

namespace clpath {
namespace {
struct CompareArgs {
    std::string a, b;
    CompareOptions options;
};
}  // namespace

Command add_compare_command(CLI::App& app) {
    auto o = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Compare image A with reference B: RMSE, PSNR (peak 1, linear), relative MSE, means, largest difference");
    cmd->add_option("image", o->a, "Image (.exr, .pfm, .png: 8-bit files are decoded from sRGB)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("reference", o->b, "Reference image")->required()->check(CLI::ExistingFile);
    cmd->add_option("--clamp", o->options.clamp, "Clamp both images to [0, V] first")->check(real_number(0, 1e9, true));
    cmd->add_option("--mask-above", o->options.mask_above,
                    "Leave out pixels where the reference exceeds V in any channel (directly seen emitters)")
        ->check(real_number(0, 1e9, true));
    cmd->add_option("--mask-grow", o->options.mask_grow,
                    "Also leave out pixels within N pixels of a masked one (an emitter's partly covered edge)")
        ->check(whole_number(0, 64));
    return [o] {
        const ImageComparison c = compare_images(read_image(o->a), read_image(o->b), o->options);
        std::printf("%s\n", describe(c).c_str());
        return 0;
    };
}

}  // namespace clpath
