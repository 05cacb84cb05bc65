// WebAssembly exceptions with threads under Debian's Emscripten 3.1.6 (clang 14): the landing-pad
// glue of libunwind, replaced (cmake/web.cmake links this file into the threaded build only).
//
// The problem. The code clang 14 generates for a `catch (T)` clause hands the pad's index and
// its LSDA to the personality function, and reads back the selector it chose, through a global,
// `__wasm_lpad_context`, which it addresses as an ordinary global. Emscripten's libunwind for
// threads (libunwind-mt-except) defines that variable thread_local, so the linker gives the
// generated code its offset in the thread-local block as an absolute address: the pads write to
// low memory, the personality reads its own (empty) context, and every typed catch fails (the
// exception escapes to JavaScript). Later compilers (LLVM 15) address it as thread-local.
//
// The remedy. The few functions of libunwind's WebAssembly part (Unwind-wasm.c) are defined
// here, so the linker does not take that file from the library, with the context an ordinary
// global, as clang 14's code expects. All threads share it, so that two never use it at once:
// a thread holds a lock from the moment it throws (_Unwind_RaiseException, the only way a C++
// exception starts: throw, rethrow, std::rethrow_exception) until a handler takes the exception
// (__cxa_begin_catch, wrapped through the linker's --wrap). Every landing pad that reads or
// writes the context runs in between, on the throwing thread. The lock is recursive: a
// destructor run during unwinding may throw and catch an exception of its own. A C++ exception
// that leaves the module uncaught would keep the lock: the bindings catch every exception at
// their boundary (web/bindings/glint_web.cpp), as a C++ program must not let one escape anyway.

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdint.h>
#include <unwind.h>

/// What the generated landing pads and the personality function exchange (the layout clang
/// and libc++abi use).
struct LandingPadContext {
    uintptr_t lpadIndex;  // in: the landing pad's index
    uintptr_t lsda;       // in: the function's language-specific data area
    uintptr_t selector;   // out: the catch clause that matched
};

struct LandingPadContext __wasm_lpad_context;

static atomic_uintptr_t owner;  // the pthread holding the context, or 0
static int depth;               // the owner's nesting (only the owner reads or writes it)

static void acquire(void) {
    uintptr_t self = (uintptr_t)pthread_self();
    if (atomic_load_explicit(&owner, memory_order_relaxed) == self) {
        ++depth;
        return;
    }
    uintptr_t expected = 0;
    while (!atomic_compare_exchange_weak_explicit(&owner, &expected, self, memory_order_acquire,
                                                  memory_order_relaxed)) {
        expected = 0;
        sched_yield();
    }
    depth = 1;
}

static void release(void) {
    if (atomic_load_explicit(&owner, memory_order_relaxed) != (uintptr_t)pthread_self()) return;
    if (--depth == 0) atomic_store_explicit(&owner, 0, memory_order_release);
}

_Unwind_Reason_Code __gxx_personality_wasm0(int version, _Unwind_Action actions,
                                            uint64_t exceptionClass,
                                            struct _Unwind_Exception* exception,
                                            struct _Unwind_Context* context);

/// Called by the landing pads of catch clauses: runs the personality function on the context
/// they filled in (WebAssembly has no two-phase unwinding: only the cleanup phase).
_Unwind_Reason_Code _Unwind_CallPersonality(void* exceptionPointer) {
    struct _Unwind_Exception* exception = exceptionPointer;
    __wasm_lpad_context.selector = 0;
    return __gxx_personality_wasm0(1, _UA_CLEANUP_PHASE, exception->exception_class, exception,
                                   (struct _Unwind_Context*)&__wasm_lpad_context);
}

/// Called by __cxa_throw and the rethrows: the exception starts here.
_Unwind_Reason_Code _Unwind_RaiseException(struct _Unwind_Exception* exception) {
    acquire();
    __builtin_wasm_throw(0, exception);
}

/// Called by __cxa_begin_catch (through its wrapper below): the exception has been caught.
void* __real___cxa_begin_catch(void* exception);
void* __wrap___cxa_begin_catch(void* exception);
void* __wrap___cxa_begin_catch(void* exception) {
    release();
    return __real___cxa_begin_catch(exception);
}

void _Unwind_DeleteException(struct _Unwind_Exception* exception) {
    if (exception->exception_cleanup)
        exception->exception_cleanup(_URC_FOREIGN_EXCEPTION_CAUGHT, exception);
}

/// The personality function's view of the context: it sets the selector (register 1), reads
/// the landing pad's index (as a 1-based "instruction pointer", after a decrement) and the LSDA.
void _Unwind_SetGR(struct _Unwind_Context* context, int index, _Unwind_Word value) {
    if (index == 1) ((struct LandingPadContext*)context)->selector = value;
}

_Unwind_Word _Unwind_GetIP(struct _Unwind_Context* context) {
    return ((struct LandingPadContext*)context)->lpadIndex + 2;
}

void _Unwind_SetIP(struct _Unwind_Context* context, _Unwind_Word value) {
    (void)context;
    (void)value;
}

void* _Unwind_GetLanguageSpecificData(struct _Unwind_Context* context) {
    return (void*)((struct LandingPadContext*)context)->lsda;
}

_Unwind_Ptr _Unwind_GetRegionStart(struct _Unwind_Context* context) {
    (void)context;
    return 0;
}
