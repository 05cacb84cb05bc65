#include "glint/denoise/unet/weights.h"

#include <map>
#include <memory>
#include <mutex>

#include "glint/denoise/unet/builtin_weights.h"

namespace glint {
namespace {

struct Registry {
    std::mutex lock;
    // Archives registered at run time; never erased or replaced in place (a span handed out
    // stays valid: replacing one keeps the old bytes alive).
    std::map<std::string, std::shared_ptr<const std::vector<uint8_t>>, std::less<>> named;
    std::vector<std::shared_ptr<const std::vector<uint8_t>>> retired;
};

Registry& registry() {
    static Registry r;
    return r;
}

}  // namespace

std::span<const uint8_t> denoiserWeights(std::string_view name) {
    {
        Registry& r = registry();
        const std::lock_guard hold(r.lock);
        const auto it = r.named.find(name);
        if (it != r.named.end()) return *it->second;
    }
    for (const unet::BuiltinWeights& w : unet::builtinWeights())
        if (w.name == name) return {w.begin, w.end};
    return {};
}

void registerDenoiserWeights(std::string name, std::vector<uint8_t> bytes) {
    Registry& r = registry();
    const std::lock_guard hold(r.lock);
    auto& slot = r.named[std::move(name)];
    if (slot) r.retired.push_back(std::move(slot));
    slot = std::make_shared<const std::vector<uint8_t>>(std::move(bytes));
}

std::vector<std::string> builtinDenoiserWeights() {
    std::vector<std::string> names;
    for (const unet::BuiltinWeights& w : unet::builtinWeights()) names.emplace_back(w.name);
    return names;
}

}  // namespace glint
