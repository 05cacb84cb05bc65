// C++ exceptions in the threaded web build (WebAssembly exceptions,
// web/bindings/wasm_eh_threads.c): typed catch clauses on several threads at once, each exception
// reaching the right handler with its own value, including an exception thrown and caught by a
// destructor while another unwinds through it, rethrows, and std::exception_ptr carried from a
// thread to another. Built by `make web` into the threaded build folder (web/CMakeLists.txt) and
// run by CTest in Node as web.wasm_exceptions_mt:
//
//   node --no-experimental-fetch build-web/mt/glint-exceptions-test.js
//
// Exit status 1 and a message on any wrong catch; an exception that escapes aborts the program.

#include <atomic>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

struct Odd {
    int value;
};

struct Even : std::runtime_error {
    int value;
    explicit Even(int v) : std::runtime_error("even " + std::to_string(v)), value(v) {}
};

std::atomic<int> failures{0};

void fail(const std::string& what) {
    if (failures++ < 10) std::printf("FAIL: %s\n", what.c_str());
}

[[gnu::noinline]] void thrower(int v) {
    if (v % 2) throw Odd{v};
    throw Even(v);
}

/// While an exception unwinds through it, throws and catches one of its own.
struct Nested {
    int v;
    ~Nested() {
        try {
            thrower(v + 1);
        } catch (const Even& e) {
            if (e.value != v + 1) fail("nested Even " + std::to_string(e.value));
        } catch (const Odd& e) {
            if (e.value != v + 1) fail("nested Odd " + std::to_string(e.value));
        }
    }
};

[[gnu::noinline]] void throwThroughNested(int v) {
    Nested n{v};
    thrower(v);
}

/// One thread's work: `rounds` exceptions of alternating types through every kind of handler.
void work(int seed, int rounds) {
    for (int i = 0; i < rounds; ++i) {
        int v = seed + 4 * i;
        try {
            throwThroughNested(v + i % 2);
        } catch (const Even& e) {
            if (i % 2 || e.value != v) fail("Even " + std::to_string(e.value));
        } catch (const Odd& e) {
            if (!(i % 2) || e.value != v + 1) fail("Odd " + std::to_string(e.value));
        }
        try {
            try {
                thrower(v);
            } catch (const std::exception&) {
                throw;  // rethrown to the outer handler
            }
        } catch (const std::runtime_error& e) {
            if (std::string(e.what()) != "even " + std::to_string(v)) fail(e.what());
        }
    }
}

}  // namespace

int main() {
    const int rounds = 20000;
    std::vector<std::thread> threads;
    std::exception_ptr carried;
    for (int t = 0; t < 2; ++t)
        threads.emplace_back([t, &carried] {
            work(1000000 * (t + 1), rounds);
            if (t == 0) {
                try {
                    throw Even(42);
                } catch (...) {
                    carried = std::current_exception();
                }
            }
        });
    work(0, rounds);
    for (std::thread& t : threads) t.join();
    try {
        std::rethrow_exception(carried);
    } catch (const Even& e) {
        if (e.value != 42) fail("carried " + std::to_string(e.value));
    }
    std::printf("%d exceptions on 3 threads: %d wrong catches\n", 3 * rounds * 3, failures.load());
    return failures ? 1 : 0;
}
