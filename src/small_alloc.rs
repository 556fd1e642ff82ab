//! A cache of small freed blocks in front of an allocator: the npm build's global allocator.
//!
//! Planning makes and drops many small vectors (trapezoid chains, swath lists, candidate
//! orders). In WebAssembly every one of them goes through dlmalloc, whose bins and coalescing
//! cost far more than the work between. [`SmallBlocks`] keeps freed blocks of up to
//! [`LARGEST`] bytes on one free list per 16-byte size class and hands them out again with a
//! pop; larger or more strictly aligned blocks go to the allocator behind it. Blocks on the
//! lists are never given back (wasm memory never shrinks anyway): the memory held is the peak
//! number of small blocks alive at once in each class, which repeated plans reach and keep.
//!
//! It is single-threaded (its constructor is `unsafe` for that): it is only the global
//! allocator on wasm32 without threads (see `lib.rs`), where nothing runs concurrently.

use std::alloc::{GlobalAlloc, Layout};
use std::cell::UnsafeCell;
use std::ptr;

/// The size classes' step, bytes.
const STEP: usize = 16;
/// The alignment of the blocks kept: dlmalloc's own on wasm32, so that every block is a plain
/// `malloc` (a more strictly aligned one would take dlmalloc's slower `memalign`).
const ALIGN: usize = 8;
/// The largest block kept on a list, bytes.
pub const LARGEST: usize = 512;
const CLASSES: usize = LARGEST / STEP;

/// Small freed blocks kept for reuse in front of the allocator `A`.
///
/// ```
/// use furrow::small_alloc::SmallBlocks;
/// use std::alloc::{GlobalAlloc, Layout, System};
///
/// let layout = Layout::from_size_align(40, 8)?;
/// unsafe {
///     // Used by this thread alone.
///     let blocks = SmallBlocks::new(System);
///     let a = blocks.alloc(layout);
///     blocks.dealloc(a, layout);
///     // The block just freed is the next one of its class.
///     assert_eq!(blocks.alloc(layout), a);
///     blocks.dealloc(a, layout);
/// }
/// # Ok::<(), std::alloc::LayoutError>(())
/// ```
pub struct SmallBlocks<A> {
    inner: A,
    /// The first free block of each class; each free block holds the next.
    heads: UnsafeCell<[*mut u8; CLASSES]>,
}

// SAFETY: whoever makes one promises that one thread at a time uses it (see `new`).
unsafe impl<A: Sync> Sync for SmallBlocks<A> {}

impl<A> SmallBlocks<A> {
    /// An empty cache in front of `inner`.
    ///
    /// # Safety
    ///
    /// The lists are not locked: the cache must only be used from one thread at a time (as the
    /// global allocator of wasm32 without threads, or a test's own).
    pub const unsafe fn new(inner: A) -> Self {
        SmallBlocks {
            inner,
            heads: UnsafeCell::new([ptr::null_mut(); CLASSES]),
        }
    }
}

/// The class of a layout, if its blocks are kept.
#[inline]
fn class_of(layout: &Layout) -> Option<usize> {
    let size = layout.size();
    if size == 0 || size > LARGEST || layout.align() > ALIGN {
        None
    } else {
        Some((size - 1) / STEP)
    }
}

/// The layout every block of class `c` is allocated with.
#[inline]
fn class_layout(c: usize) -> Layout {
    // SAFETY: the size is a non-zero multiple of 16 below isize::MAX, the alignment a power of two.
    unsafe { Layout::from_size_align_unchecked((c + 1) * STEP, ALIGN) }
}

unsafe impl<A: GlobalAlloc> GlobalAlloc for SmallBlocks<A> {
    #[inline(never)]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let Some(c) = class_of(&layout) else {
            return self.inner.alloc(layout);
        };
        // Through the raw pointer, with no reference to the lists held while `inner` runs.
        let heads = self.heads.get();
        let head = (*heads)[c];
        if head.is_null() {
            self.inner.alloc(class_layout(c))
        } else {
            (*heads)[c] = *(head as *mut *mut u8);
            head
        }
    }

    #[inline(never)]
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        let Some(c) = class_of(&layout) else {
            return self.inner.dealloc(ptr, layout);
        };
        let heads = self.heads.get();
        *(ptr as *mut *mut u8) = (*heads)[c];
        (*heads)[c] = ptr;
    }

    #[inline(never)]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        match class_of(&layout) {
            None => self.inner.alloc_zeroed(layout),
            Some(_) => {
                let p = self.alloc(layout);
                if !p.is_null() {
                    ptr::write_bytes(p, 0, layout.size());
                }
                p
            }
        }
    }

    #[inline(never)]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller promises new_size rounded to the alignment fits isize.
        let new_layout = Layout::from_size_align_unchecked(new_size, layout.align());
        match (class_of(&layout), class_of(&new_layout)) {
            // Neither kept here: the allocator behind grows the block in place where it can.
            (None, None) => self.inner.realloc(ptr, layout, new_size),
            // The same class: the block already has room.
            (Some(a), Some(b)) if a == b => ptr,
            _ => {
                let new = self.alloc(new_layout);
                if !new.is_null() {
                    ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
                    self.dealloc(ptr, layout);
                }
                new
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::alloc::System;

    #[test]
    fn blocks_are_reused_by_class_and_keep_their_contents_through_realloc() {
        let l = |size, align| Layout::from_size_align(size, align).unwrap();
        unsafe {
            // This test's own: one thread.
            let blocks = SmallBlocks::new(System);
            // 17 to 32 bytes are one class; 33 another.
            let a = blocks.alloc(l(20, 4));
            let b = blocks.alloc(l(32, 8));
            assert!(!a.is_null() && !b.is_null() && a != b);
            assert!((a as usize).is_multiple_of(ALIGN));
            blocks.dealloc(a, l(20, 4));
            assert_eq!(blocks.alloc(l(17, 1)), a, "the same class: the freed block");
            let c = blocks.alloc(l(33, 8));
            assert!(c != a && c != b);
            // Growing within the class keeps the block; beyond it moves, contents and all.
            for i in 0..20u8 {
                *a.add(usize::from(i)) = i;
            }
            assert_eq!(blocks.realloc(a, l(17, 1), 30), a);
            let moved = blocks.realloc(a, l(30, 1), 300);
            assert!(moved != a);
            for i in 0..20u8 {
                assert_eq!(*moved.add(usize::from(i)), i);
            }
            // Into a large block and back.
            let large = blocks.realloc(moved, l(300, 1), 4000);
            assert_eq!(*large.add(19), 19);
            let small = blocks.realloc(large, l(4000, 1), 24);
            assert_eq!(*small.add(7), 7);
            // Zeroed blocks are zero even when reused.
            *b = 0xff;
            blocks.dealloc(b, l(32, 8));
            let z = blocks.alloc_zeroed(l(32, 8));
            assert_eq!(z, b);
            assert!((0..32).all(|i| *z.add(i) == 0));
            // Over-aligned layouts are the allocator's own: a block freed to a list (and held
            // there) is not handed out for one.
            let kept = blocks.alloc(l(48, 8));
            blocks.dealloc(kept, l(48, 8));
            let wide = blocks.alloc(l(48, 64));
            assert!(wide != kept && (wide as usize).is_multiple_of(64));
            blocks.dealloc(wide, l(48, 64));
            assert_eq!(blocks.alloc(l(48, 8)), kept);
            blocks.dealloc(kept, l(48, 8));
            for (p, layout) in [(small, l(24, 1)), (z, l(32, 8)), (c, l(33, 8))] {
                blocks.dealloc(p, layout);
            }
        }
    }
}
