//! The allocator of static musl builds: Doug Lea's malloc (the `dlmalloc`
//! crate) behind one lock, with a small per-thread cache of freed blocks.
//!
//! musl's own malloc maps and unmaps memory eagerly (a coarse paving spent
//! much of its time in `mmap`/`munmap` and page faults) and mimalloc touches
//! about a hundred pages before `main`; dlmalloc grows its heap as glibc's
//! does. Under its one lock two paving threads waited on each other, so
//! blocks of up to [`MAX_CACHED`] bytes are kept per thread, by size class,
//! and move between a thread and the heap [`BATCH`] at a time. All blocks
//! come from the one heap: a block freed on another thread than its own is
//! simply cached there. Blocks that grow past [`MAPPED`] bytes move to
//! mappings of their own, which grow without copying.

use dlmalloc::{Allocator, Dlmalloc};
use std::alloc::{GlobalAlloc, Layout};
use std::cell::UnsafeCell;
use std::ptr;
use std::sync::{Mutex, MutexGuard};

/// Size classes of [`GRAIN`] bytes up to this size are cached per thread.
const MAX_CACHED: usize = 512;
const GRAIN: usize = 16;
const CLASSES: usize = MAX_CACHED / GRAIN;
/// Blocks moved per lock: a refill of an empty class, or the spill of a
/// class holding [`DEPTH`] blocks.
const BATCH: u32 = 32;
/// At most this many blocks per class and thread (32 × 64 × 512 B / 2 =
/// 0.5 MiB at most, far less in practice).
const DEPTH: u32 = 2 * BATCH;
/// Blocks growing to this size or more move to a mapping of their own
/// (see [`Maps`]).
const MAPPED: usize = 256 << 10;
const PAGE: usize = 4096;

/// The global allocator (see the module documentation).
pub struct CachedDlmalloc;

/// System memory for dlmalloc: anonymous mappings, never given back.
/// Returned pages were mapped afresh (and faulted in again) when a paving's
/// next, larger level needed them; glibc's heap keeps them. The heap stays
/// at its peak size.
struct Retain;

// SAFETY: `alloc` returns fresh zeroed private mappings of the size it
// reports, `remap` is `mremap`'s contract, and every release reports
// failure, which the trait allows (the memory stays with the heap).
unsafe impl Allocator for Retain {
    fn alloc(&self, size: usize) -> (*mut u8, usize, u32) {
        // SAFETY: a new anonymous mapping aliases nothing.
        let p = unsafe { map(size) };
        (p, if p.is_null() { 0 } else { size }, 0)
    }
    fn remap(&self, p: *mut u8, oldsize: usize, newsize: usize, can_move: bool) -> *mut u8 {
        // SAFETY: `p` and `oldsize` describe one of this allocator's mappings.
        unsafe { remap(p, oldsize, newsize, can_move) }
    }
    fn free_part(&self, _: *mut u8, _: usize, _: usize) -> bool {
        false
    }
    fn free(&self, _: *mut u8, _: usize) -> bool {
        false
    }
    fn can_release_part(&self, _: u32) -> bool {
        false
    }
    fn allocates_zeros(&self) -> bool {
        true
    }
    fn page_size(&self) -> usize {
        PAGE
    }
}

/// dlmalloc's state holds raw pointers into its own heap; it is only ever
/// used under [`HEAP`]'s lock.
struct Heap(Dlmalloc<Retain>);
// SAFETY: the heap is reached only through the mutex below.
unsafe impl Send for Heap {}

static HEAP: Mutex<Heap> = Mutex::new(Heap(Dlmalloc::new_with_allocator(Retain)));

/// The heap, locked (a panic elsewhere leaves dlmalloc consistent: it does
/// not unwind from inside an allocation).
fn heap() -> MutexGuard<'static, Heap> {
    HEAP.lock().unwrap_or_else(|e| e.into_inner())
}

#[derive(Clone, Copy)]
struct FreeList {
    /// First free block; each block's first word points to the next.
    head: *mut u8,
    len: u32,
}

struct Cache(UnsafeCell<[FreeList; CLASSES]>);

thread_local! {
    // Const-initialised and without `Drop`: no allocation and no destructor
    // registration, so usable inside the allocator. A thread's cached
    // blocks stay allocated when it exits (bounded above).
    static CACHE: Cache = const {
        Cache(UnsafeCell::new([FreeList { head: ptr::null_mut(), len: 0 }; CLASSES]))
    };
}

/// The size class of `layout` (its size rounded up to [`GRAIN`]), if cached.
fn class(layout: &Layout) -> Option<usize> {
    let size = layout.size();
    (size != 0 && size <= MAX_CACHED && layout.align() <= GRAIN).then(|| (size - 1) / GRAIN)
}

/// The size of a block of class `c`.
fn class_size(c: usize) -> usize {
    (c + 1) * GRAIN
}

impl FreeList {
    /// SAFETY: `block` is a free block of this list's class, owned by the caller.
    unsafe fn push(&mut self, block: *mut u8) {
        *(block as *mut *mut u8) = self.head;
        self.head = block;
        self.len += 1;
    }

    /// SAFETY: the list is not empty.
    unsafe fn pop(&mut self) -> *mut u8 {
        let block = self.head;
        self.head = *(block as *mut *mut u8);
        self.len -= 1;
        block
    }
}

/// Blocks that grew to [`MAPPED`] bytes or more by `realloc`: each its own
/// mapping, so that growing further is `mremap`, which copies nothing. (From
/// dlmalloc's heap a growing tree was copied at every doubling, serially,
/// and two threads gained less.) Allocated at that size directly, a block
/// stays in the heap, whose freed memory the next paving level reuses
/// without faulting pages in afresh. As glibc's malloc, which also maps
/// large blocks but raises its threshold to the size of those freed.
struct Maps {
    /// Start and length of each mapping; length 0 marks a free slot.
    at: [(usize, usize); MAPS],
}

/// At most this many mappings at once; a block growing past [`MAPPED`]
/// when all are taken stays in the heap (copied as it grows).
const MAPS: usize = 64;

static MAPPINGS: Mutex<Maps> = Mutex::new(Maps { at: [(0, 0); MAPS] });

fn mappings() -> MutexGuard<'static, Maps> {
    MAPPINGS.lock().unwrap_or_else(|e| e.into_inner())
}

impl Maps {
    fn find(&self, block: *mut u8) -> Option<usize> {
        self.at
            .iter()
            .position(|&(p, n)| n != 0 && p == block as usize)
    }
}

/// A fresh zeroed mapping of `size` bytes, or null.
unsafe fn map(size: usize) -> *mut u8 {
    let prot = libc::PROT_READ | libc::PROT_WRITE;
    let flags = libc::MAP_PRIVATE | libc::MAP_ANONYMOUS;
    or_null(libc::mmap(ptr::null_mut(), size, prot, flags, -1, 0))
}

/// The mapping `p` of `old` bytes resized to `new` (moved if `can_move`),
/// or null (`p` unchanged).
unsafe fn remap(p: *mut u8, old: usize, new: usize, can_move: bool) -> *mut u8 {
    let flags = if can_move { libc::MREMAP_MAYMOVE } else { 0 };
    or_null(libc::mremap(p.cast(), old, new, flags))
}

fn or_null(p: *mut libc::c_void) -> *mut u8 {
    if p == libc::MAP_FAILED {
        ptr::null_mut()
    } else {
        p.cast()
    }
}

impl CachedDlmalloc {
    /// A block of class `c`, from this thread's cache (refilled from the
    /// heap when empty).
    unsafe fn take(c: usize) -> *mut u8 {
        CACHE.with(|cache| {
            // SAFETY: only this thread touches its cache, and not
            // reentrantly (nothing below allocates through it).
            let list = &mut (*cache.0.get())[c];
            if list.len == 0 {
                let mut h = heap();
                for _ in 0..BATCH {
                    let block = h.0.malloc(class_size(c), GRAIN);
                    if block.is_null() {
                        break;
                    }
                    list.push(block);
                }
                if list.len == 0 {
                    return ptr::null_mut();
                }
            }
            list.pop()
        })
    }

    /// Returns a block of class `c` to this thread's cache (spilling to the
    /// heap when full).
    unsafe fn give(block: *mut u8, c: usize) {
        CACHE.with(|cache| {
            // SAFETY: as in `take`; a block is at least one word (GRAIN
            // bytes) and aligned to GRAIN.
            let list = &mut (*cache.0.get())[c];
            list.push(block);
            if list.len >= DEPTH {
                let mut h = heap();
                for _ in 0..BATCH {
                    h.0.free(list.pop(), class_size(c), GRAIN);
                }
            }
        })
    }

    /// Resizes a block that is one of [`MAPPINGS`], if it is one: `None`
    /// if it is not, else the new block (null on failure, the old one kept).
    unsafe fn resize_mapped(&self, block: *mut u8, layout: Layout, size: usize) -> Option<*mut u8> {
        if layout.size() < MAPPED {
            return None;
        }
        let mut maps = mappings();
        let k = maps.find(block)?;
        if size >= MAPPED {
            let q = remap(block, layout.size(), size, true);
            if !q.is_null() {
                maps.at[k] = (q as usize, size);
            }
            return Some(q);
        }
        // Shrunk below the threshold: back to the heap, so that every
        // mapping is at least MAPPED bytes (what `dealloc` relies on).
        drop(maps);
        Some(self.moved(block, layout, size))
    }

    /// `block` copied into a new allocation of `size` bytes and freed; null
    /// (the block kept) if none is available.
    unsafe fn moved(&self, block: *mut u8, layout: Layout, size: usize) -> *mut u8 {
        // SAFETY: the caller guarantees `size` is valid for the alignment.
        let q = self.alloc(Layout::from_size_align_unchecked(size, layout.align()));
        if !q.is_null() {
            ptr::copy_nonoverlapping(block, q, layout.size().min(size));
            self.dealloc(block, layout);
        }
        q
    }

    /// Moves a block growing to `size` ≥ [`MAPPED`] into a mapping of its
    /// own, if a slot is free; `None` otherwise.
    unsafe fn grow_into_mapping(
        &self,
        block: *mut u8,
        layout: Layout,
        size: usize,
    ) -> Option<*mut u8> {
        if size < MAPPED || layout.align() > PAGE {
            return None;
        }
        let mut maps = mappings();
        let k = maps.at.iter().position(|&(_, n)| n == 0)?;
        let q = map(size);
        if q.is_null() {
            return None;
        }
        maps.at[k] = (q as usize, size);
        drop(maps);
        ptr::copy_nonoverlapping(block, q, layout.size());
        self.dealloc(block, layout);
        Some(q)
    }
}

unsafe impl GlobalAlloc for CachedDlmalloc {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        match class(&layout) {
            Some(c) => Self::take(c),
            None => heap().0.malloc(layout.size(), layout.align()),
        }
    }

    #[inline]
    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        if let Some(c) = class(&layout) {
            return Self::give(block, c);
        }
        if layout.size() >= MAPPED {
            let mut maps = mappings();
            if let Some(k) = maps.find(block) {
                maps.at[k] = (0, 0);
                drop(maps);
                // SAFETY: one of this allocator's mappings, of this size.
                libc::munmap(block.cast(), layout.size());
                return;
            }
        }
        heap().0.free(block, layout.size(), layout.align())
    }

    #[inline]
    unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if let Some(q) = self.resize_mapped(block, layout, new_size) {
            return q;
        }
        if new_size > layout.size() {
            if let Some(q) = self.grow_into_mapping(block, layout, new_size) {
                return q;
            }
        }
        // SAFETY: the caller guarantees `new_size` is valid for the alignment.
        let new = Layout::from_size_align_unchecked(new_size, layout.align());
        match (class(&layout), class(&new)) {
            // dlmalloc resizes in place when it can.
            (None, None) => heap()
                .0
                .realloc(block, layout.size(), layout.align(), new_size),
            // Same class: the block already has room.
            (Some(a), Some(b)) if a == b => block,
            _ => self.moved(block, layout, new_size),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_round_up_to_the_grain_and_stop_at_the_limit() {
        let l = |s, a| Layout::from_size_align(s, a).unwrap();
        assert_eq!(class(&l(1, 1)), Some(0));
        assert_eq!(class(&l(16, 8)), Some(0));
        assert_eq!(class(&l(17, 8)), Some(1));
        assert_eq!(class(&l(512, 16)), Some(CLASSES - 1));
        assert_eq!(class(&l(513, 8)), None);
        assert_eq!(class(&l(0, 1)), None);
        assert_eq!(
            class(&l(64, 32)),
            None,
            "over-aligned blocks bypass the cache"
        );
    }

    /// Blocks of every size, allocated, written, resized across classes and
    /// freed on several threads (some freed on another thread than their
    /// own): contents survive and no two live blocks overlap.
    #[test]
    fn blocks_stay_distinct_and_keep_their_contents_across_threads() {
        let a = &CachedDlmalloc;
        let sizes: Vec<usize> = (1..=700).step_by(7).collect();
        let handoff: Vec<(usize, usize)> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..3)
                .map(|t| {
                    let sizes = &sizes;
                    s.spawn(move || {
                        let mut live: Vec<(usize, usize)> = Vec::new();
                        for round in 0..50 {
                            for &n in sizes {
                                let l = Layout::from_size_align(n, 8).unwrap();
                                // SAFETY: non-zero size; written within bounds.
                                let p = unsafe { a.alloc(l) };
                                assert!(!p.is_null());
                                let tag = (t * 31 + round + n) as u8;
                                unsafe { ptr::write_bytes(p, tag, n) };
                                live.push((p as usize, n));
                            }
                            // Grow every other block into another class.
                            for (i, (p, n)) in live.iter_mut().enumerate().step_by(2) {
                                let l = Layout::from_size_align(*n, 8).unwrap();
                                let m = *n + 40 * (i % 5) + 1;
                                // SAFETY: a live block of layout `l`.
                                let q = unsafe { a.realloc(*p as *mut u8, l, m) };
                                let first = unsafe { *q };
                                let last = unsafe { *q.add(*n - 1) };
                                assert_eq!(first, last, "contents kept by realloc");
                                unsafe { ptr::write_bytes(q, first, m) };
                                (*p, *n) = (q as usize, m);
                            }
                            // Free half, keep half for the next round.
                            let keep = live.split_off(live.len() / 2);
                            for (p, n) in live {
                                let l = Layout::from_size_align(n, 8).unwrap();
                                unsafe { a.dealloc(p as *mut u8, l) };
                            }
                            live = keep;
                            let mut spans: Vec<_> = live.iter().map(|&(p, n)| (p, p + n)).collect();
                            spans.sort_unstable();
                            assert!(spans.windows(2).all(|w| w[0].1 <= w[1].0), "blocks overlap");
                            for &(p, n) in &live {
                                let b = unsafe { std::slice::from_raw_parts(p as *const u8, n) };
                                assert!(b.iter().all(|&x| x == b[0]), "contents changed");
                            }
                        }
                        live
                    })
                })
                .collect();
            hs.into_iter().flat_map(|h| h.join().unwrap()).collect()
        });
        // Freed here, on another thread than the one that allocated them.
        for (p, n) in handoff {
            let l = Layout::from_size_align(n, 8).unwrap();
            unsafe { a.dealloc(p as *mut u8, l) };
        }
    }

    /// Large blocks: zeroed when asked, contents kept when they grow or
    /// shrink across the mapped/heap/cached boundaries, mappings released.
    #[test]
    fn large_blocks_are_zeroed_and_keep_their_contents_when_resized() {
        let a = &CachedDlmalloc;
        let l = |n| Layout::from_size_align(n, 8).unwrap();
        let mapped = || mappings().at.iter().filter(|m| m.1 != 0).count();
        // Sizes through every kind and back: 3 MiB, 300 KiB, 600 B, 40 B, 1 MiB.
        let sizes = [3 << 20, 300 << 10, 600, 40, 1 << 20, 5 << 20];
        // SAFETY: every pointer is used within the size it was given.
        unsafe {
            let mut n = MAPPED + 5;
            let mut p = a.alloc_zeroed(l(n));
            assert!(!p.is_null());
            assert!(std::slice::from_raw_parts(p, n).iter().all(|&x| x == 0));
            let before = mapped();
            for (k, &m) in sizes.iter().enumerate() {
                for i in 0..n {
                    *p.add(i) = (i * 7 + k) as u8;
                }
                let q = a.realloc(p, l(n), m);
                assert!(!q.is_null());
                for i in 0..n.min(m) {
                    assert_eq!(*q.add(i), (i * 7 + k) as u8, "byte {i} after {n} -> {m}");
                }
                (p, n) = (q, m);
            }
            // Grown from 1 MiB to 5 MiB: a mapping of its own (other tests
            // may hold mappings too, hence at least).
            assert!(mapped() > before.saturating_sub(1));
            assert!(mappings().find(p).is_some(), "a grown block is mapped");
            a.dealloc(p, l(n));
            assert!(mappings().find(p).is_none(), "its slot is released");
        }
    }
}
