#include "glint/core/input_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include "glint/core/mapped_file.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& contents) {
    fs::path p = fs::temp_directory_path() / ("glint_input_log_" + name);
    std::ofstream(p, std::ios::binary) << contents;
    return p;
}

TEST(InputLog, HashBytesTellsApartEveryLengthAndEverySingleBitChange) {
    std::string text(100, 'a');
    std::set<uint64_t> seen;
    for (size_t n = 0; n <= text.size(); ++n)
        seen.insert(hashBytes(std::string_view(text).substr(0, n)));
    EXPECT_EQ(seen.size(), text.size() + 1);  // every prefix, zero bytes included
    const uint64_t base = hashBytes(text);
    for (size_t i = 0; i < text.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            std::string flipped = text;
            flipped[i] = static_cast<char>(flipped[i] ^ (1 << bit));
            ASSERT_NE(hashBytes(flipped), base) << i << " " << bit;
        }
    EXPECT_EQ(hashBytes(std::string(text)), base);  // equal bytes, equal hash
    EXPECT_NE(hashBytes(text, 1), base);            // the seed matters
}

TEST(InputLog, RecordsEveryMappedFileWhileAliveAndHashesContentsNotPathsOrOrder) {
    const fs::path a = writeFile("a.txt", "sphere 0 0 0 1\n"), b = writeFile("b.txt", "");
    const fs::path a2 = writeFile("a_copy.txt", "sphere 0 0 0 1\n");
    { MappedFile before(a.string()); }  // no log: not recorded anywhere
    uint64_t first = 0;
    {
        InputLog log;
        EXPECT_THROW(InputLog second, std::logic_error);
        MappedFile fa(a.string()), fb(b.string());
        const auto records = log.records();
        ASSERT_EQ(records.size(), 2u);
        EXPECT_EQ(records[0].path, a.string());
        EXPECT_EQ(records[0].bytes, 15u);
        EXPECT_EQ(records[0].hash, hashBytes("sphere 0 0 0 1\n"));
        EXPECT_EQ(records[1].bytes, 0u);
        first = log.hash();
    }
    {
        InputLog log;  // the same contents under another name, opened in the other order
        MappedFile fb(b.string()), fa(a2.string());
        EXPECT_EQ(log.records().size(), 2u);
        EXPECT_EQ(log.hash(), first);
    }
    {
        InputLog log;
        const fs::path changed = writeFile("a_changed.txt", "sphere 0 0 0 2\n");
        MappedFile fa(changed.string()), fb(b.string());
        EXPECT_NE(log.hash(), first);
        fs::remove(changed);
    }
    for (const fs::path& p : {a, b, a2}) fs::remove(p);
}

}  // namespace
}  // namespace glint
