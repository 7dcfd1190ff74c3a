// Replaces global operator new/delete and (outside sanitizer builds) the C
// allocator's entry points of this binary with counting forwarders to
// glibc's own allocator (__libc_malloc & co), see alloc_guard.hpp.
#include "tests/tick_alloc/alloc_guard.hpp"

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> g_armed{false};
std::atomic<long> g_heap_calls{0};

void note_heap_call() noexcept {
  if (g_armed.load(std::memory_order_relaxed)) g_heap_calls.fetch_add(1, std::memory_order_relaxed);
}

// operator new goes through malloc: counted there when malloc is replaced, here otherwise.
void* new_block(std::size_t n) {
  if (!tnv::test::kMallocCounted) note_heap_call();
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* new_aligned_block(std::size_t n, std::align_val_t a) {
  if (!tnv::test::kMallocCounted) note_heap_call();
  const auto align = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(align, ((n + align - 1) / align) * align)) return p;
  throw std::bad_alloc();
}
void* nothrow_block(std::size_t n) noexcept {
  if (!tnv::test::kMallocCounted) note_heap_call();
  return std::malloc(n == 0 ? 1 : n);
}
void* nothrow_aligned_block(std::size_t n, std::align_val_t a) noexcept {
  if (!tnv::test::kMallocCounted) note_heap_call();
  const auto align = static_cast<std::size_t>(a);
  return std::aligned_alloc(align, ((n + align - 1) / align) * align);
}
void delete_block(void* p) noexcept {
  if (!tnv::test::kMallocCounted && p != nullptr) note_heap_call();
  std::free(p);
}
}  // namespace

namespace tnv::test {
void arm_allocation_guard() noexcept {
  g_heap_calls = 0;
  g_armed = true;
}
long disarm_allocation_guard() noexcept {
  g_armed = false;
  return g_heap_calls.load();
}
}  // namespace tnv::test

void* operator new(std::size_t n) { return new_block(n); }
void* operator new[](std::size_t n) { return new_block(n); }
void* operator new(std::size_t n, std::align_val_t a) { return new_aligned_block(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return new_aligned_block(n, a); }
// The nothrow forms too (std::stable_sort's buffer uses them): under a
// sanitizer an unreplaced nothrow new would allocate in the sanitizer's
// operator new and be freed here through free(), a mismatch it reports.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return nothrow_block(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return nothrow_block(n); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return nothrow_aligned_block(n, a);
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return nothrow_aligned_block(n, a);
}
void operator delete(void* p, const std::nothrow_t&) noexcept { delete_block(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { delete_block(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { delete_block(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { delete_block(p); }
void operator delete(void* p) noexcept { delete_block(p); }
void operator delete[](void* p) noexcept { delete_block(p); }
void operator delete(void* p, std::size_t) noexcept { delete_block(p); }
void operator delete[](void* p, std::size_t) noexcept { delete_block(p); }
void operator delete(void* p, std::align_val_t) noexcept { delete_block(p); }
void operator delete[](void* p, std::align_val_t) noexcept { delete_block(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { delete_block(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { delete_block(p); }

#if !defined(TNV_SANITIZER_OWNS_MALLOC)
// glibc's allocator under its internal names: what malloc & co are when
// nothing replaces them.
extern "C" {
void* __libc_malloc(std::size_t n) noexcept;
void* __libc_calloc(std::size_t count, std::size_t n) noexcept;
void* __libc_realloc(void* p, std::size_t n) noexcept;
void __libc_free(void* p) noexcept;
void* __libc_memalign(std::size_t align, std::size_t n) noexcept;

void* malloc(std::size_t n) noexcept {
  note_heap_call();
  return __libc_malloc(n);
}
void* calloc(std::size_t count, std::size_t n) noexcept {
  note_heap_call();
  return __libc_calloc(count, n);
}
void* realloc(void* p, std::size_t n) noexcept {
  note_heap_call();
  return __libc_realloc(p, n);
}
void free(void* p) noexcept {
  if (p != nullptr) note_heap_call();
  __libc_free(p);
}
void* aligned_alloc(std::size_t align, std::size_t n) noexcept {
  note_heap_call();
  return __libc_memalign(align, n);
}
void* memalign(std::size_t align, std::size_t n) noexcept {
  note_heap_call();
  return __libc_memalign(align, n);
}
int posix_memalign(void** out, std::size_t align, std::size_t n) noexcept {
  note_heap_call();
  if (align < sizeof(void*) || (align & (align - 1)) != 0) return EINVAL;
  void* p = __libc_memalign(align, n);
  if (p == nullptr) return ENOMEM;
  *out = p;
  return 0;
}
}  // extern "C"
#endif
