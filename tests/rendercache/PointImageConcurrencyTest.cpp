// The Render Cache's depth test from several plain threads at once, built
// under ThreadSanitizer too (the tsan preset): offers race on the same
// pixels, and the image must end as one thread would leave it.
#include <gtest/gtest.h>

#include <cstdint>
#include <thread>
#include <vector>

#include "rendercache/PointImage.h"
#include "rendercache/RequestMap.h"

using namespace raycache;

namespace {

struct Offer {
    int x, y;
    float depth;
    std::uint32_t slot;
};

std::vector<Offer> makeOffers(int count, int width, int height) {
    std::vector<Offer> offers;
    for (int i = 0; i < count; ++i) {
        const std::uint64_t h = mixBits(static_cast<std::uint64_t>(i));
        // Few pixels, few depth values: many offers collide, many tie.
        offers.push_back({static_cast<int>(h % static_cast<std::uint64_t>(width)),
                          static_cast<int>((h >> 16) % static_cast<std::uint64_t>(height)),
                          1.0f + static_cast<float>((h >> 32) % 7u), static_cast<std::uint32_t>(i)});
    }
    return offers;
}

}  // namespace

TEST(PointImageConcurrency, FourThreadsLeaveWhatOneThreadLeaves) {
    constexpr int kWidth = 16, kHeight = 8, kMargin = 1;
    const std::vector<Offer> offers = makeOffers(40000, kWidth, kHeight);
    PointImage serial;
    serial.reset(kWidth, kHeight, kMargin);
    for (const Offer& o : offers) serial.offer(o.x, o.y, o.depth, o.slot);

    for (int round = 0; round < 5; ++round) {
        PointImage shared;
        shared.reset(kWidth, kHeight, kMargin);
        constexpr int kThreads = 4;
        std::vector<std::thread> threads;
        for (int t = 0; t < kThreads; ++t)
            threads.emplace_back([&, t] {
                for (std::size_t i = static_cast<std::size_t>(t); i < offers.size(); i += kThreads)
                    shared.offer(offers[i].x, offers[i].y, offers[i].depth, offers[i].slot);
            });
        for (std::thread& th : threads) th.join();
        for (int y = -kMargin; y < kHeight + kMargin; ++y)
            for (int x = -kMargin; x < kWidth + kMargin; ++x)
                ASSERT_EQ(shared.keyAt(x, y), serial.keyAt(x, y)) << x << "," << y << " round " << round;
    }
}
