#include "glint/denoise/network_denoise.h"

#include <map>
#include <mutex>
#include <stdexcept>

#include "glint/denoise/unet/unet.h"
#include "glint/denoise/unet/unet_filter.h"
#include "glint/denoise/unet/weights.h"

namespace glint {

std::string_view denoiseQualityName(DenoiseQuality quality) {
    switch (quality) {
        case DenoiseQuality::Fast:
            return "fast";
        case DenoiseQuality::Balanced:
            return "balanced";
        case DenoiseQuality::High:
            return "high";
    }
    return "?";
}

DenoiseQuality denoiseQualityNamed(std::string_view name) {
    for (DenoiseQuality q : {DenoiseQuality::Fast, DenoiseQuality::Balanced, DenoiseQuality::High})
        if (denoiseQualityName(q) == name) return q;
    throw std::invalid_argument("no denoising quality '" + std::string(name) +
                                "' (fast, balanced, high)");
}

NetworkChoice networkChoice(DenoiseQuality quality, bool albedo, bool normal) {
    const std::string suffix = quality == DenoiseQuality::Fast ? "_small" : "";
    if (albedo && normal) {
        if (quality == DenoiseQuality::High)
            return {"rt_hdr_calb_cnrm_large", "rt_alb_large", "rt_nrm_large"};
        return {"rt_hdr_alb_nrm" + suffix, "", ""};
    }
    return {(albedo ? "rt_hdr_alb" : "rt_hdr") + suffix, "", ""};
}

bool networkWeightsHere(const NetworkChoice& choice) {
    for (const std::string* name : {&choice.color, &choice.albedo, &choice.normal})
        if (!name->empty() && denoiserWeights(*name).empty()) return false;
    return true;
}

bool networkDenoiserAvailable(DenoiseQuality quality) {
    for (int passes = 0; passes < 3; ++passes)
        if (!networkWeightsHere(networkChoice(quality, passes > 0, passes > 1))) return false;
    return true;
}

std::shared_ptr<const UNet> denoiserNetwork(std::string_view name) {
    static std::mutex lock;
    static std::map<std::string, std::shared_ptr<const UNet>, std::less<>> cache;
    const std::lock_guard hold(lock);
    const auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    const std::span<const uint8_t> bytes = denoiserWeights(name);
    if (bytes.empty())
        throw std::runtime_error(
            "this build of Glint has no weights '" + std::string(name) +
            "' for the network denoiser (denoise-weights/fetch.sh fetches them; then build "
            "again), so use --denoiser nlm");
    auto net = std::make_shared<const UNet>(UNet::fromTensors(parseTza(bytes, std::string(name))));
    cache.emplace(std::string(name), net);
    return net;
}

NetworkDenoised networkDenoise(const DenoiseInput& in, DenoiseQuality quality, ThreadPool& pool) {
    if (in.width <= 0 || in.height <= 0 || !in.color)
        throw std::invalid_argument("networkDenoise: no image");
    const NetworkChoice choice =
        networkChoice(quality, in.albedo != nullptr, in.albedo && in.normal);
    NetworkDenoised out;
    // Clean passes first, where the colour's network was trained on clean ones.
    auto clean = [&](const std::string& name, const Vec3* pass, UNetRole role) {
        UNetImages images{in.width, in.height, pass, nullptr, nullptr, role};
        UNetResult r = unetDenoise(*denoiserNetwork(name), images, pool);
        out.nonFinite = std::max(out.nonFinite, r.nonFinite);
        return std::move(r.pixels);
    };
    std::vector<Vec3> albedo, normal;
    if (!choice.albedo.empty()) albedo = clean(choice.albedo, in.albedo, UNetRole::Albedo);
    if (!choice.normal.empty()) normal = clean(choice.normal, in.normal, UNetRole::Normal);
    UNetImages images{in.width,
                      in.height,
                      in.color,
                      albedo.empty() ? in.albedo : albedo.data(),
                      normal.empty() ? in.normal : normal.data(),
                      UNetRole::HdrColor};
    UNetResult r = unetDenoise(*denoiserNetwork(choice.color), images, pool);
    out.nonFinite = std::max(out.nonFinite, r.nonFinite);
    out.color = std::move(r.pixels);
    return out;
}

}  // namespace glint
