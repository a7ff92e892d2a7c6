//! Large read-only arrays on 2 MiB pages: the nodes and leaves of a mesh BVH.
//!
//! Incoherent rays touch a tree of tens of megabytes at random, and with 4 KiB pages
//! nearly every node they load also misses the TLB (a few thousand entries cover a few
//! megabytes), so each cache miss costs a page walk too. Embree asks Linux for
//! transparent huge pages for its BVH memory; [`PageArray`] does the same: on Linux, an
//! array of at least [`MIN_MAPPED`] bytes is copied into its own anonymous mapping, marked
//! `MADV_HUGEPAGE` before it is first touched, so the kernel backs it with 2 MiB pages
//! where transparent huge pages are enabled (`always` or `madvise`). A [`PageBuffer`]
//! fills such a mapping directly, slice by slice, so a large array is written once, with no
//! 4 KiB page faults and no copy. Elsewhere, when the mapping fails, and for small arrays
//! it is a plain `Vec`. The contents are the same either way: only the speed differs.

use std::ops::Deref;

/// The huge page size the mapping is aligned to (x86-64 and aarch64 with 4 KiB base pages).
pub const HUGE_PAGE: usize = 2 << 20;

/// The smallest array given its own mapping: a smaller one is mostly covered by the TLB's
/// 4 KiB entries, and its last, partly used huge page would waste a larger share (here at
/// most a third). Two huge pages, so that the nodes of a million-triangle mesh (about
/// 5 MiB, beside some 50 MiB of leaves competing for the TLB) are mapped too: at four
/// they were not, and incoherent rays through the terrain of `benches/mesh_bvh.rs` were
/// slower in five of six alternating runs, by about 4 % (the dragon's within the noise).
pub const MIN_MAPPED: usize = 2 * HUGE_PAGE;

/// An immutable array of `T`, on huge pages where the system gives them.
pub struct PageArray<T: Copy> {
    storage: Storage<T>,
}

enum Storage<T: Copy> {
    Heap(Vec<T>),
    #[cfg(target_os = "linux")]
    Mapped(mapped::Mapping<T>),
}

impl<T: Copy> PageArray<T> {
    /// The array holding `items` (copied to huge pages when it is large, kept otherwise).
    pub fn new(items: Vec<T>) -> Self {
        #[cfg(target_os = "linux")]
        if std::mem::size_of_val(items.as_slice()) >= MIN_MAPPED
            && let Some(mapping) = mapped::Mapping::copy_of(&items)
        {
            return Self { storage: Storage::Mapped(mapping) };
        }
        Self { storage: Storage::Heap(items) }
    }

    /// True when the array lives in its own huge-page mapping.
    #[cfg(test)]
    pub fn is_mapped(&self) -> bool {
        !matches!(self.storage, Storage::Heap(_))
    }
}

/// A growable array that becomes a [`PageArray`]: when `capacity` items would fill at
/// least [`MIN_MAPPED`] bytes it writes straight into a huge-page mapping reserved for them
/// (address space only: untouched pages cost no memory), and moves to the heap when it
/// ends up smaller than that.
pub struct PageBuffer<T: Copy> {
    storage: Storage<T>,
}

impl<T: Copy> PageBuffer<T> {
    /// An empty buffer for up to `capacity` items (more may be pushed, at the cost of a copy
    /// to the heap).
    pub fn with_capacity(capacity: usize) -> Self {
        #[cfg(target_os = "linux")]
        if capacity.saturating_mul(std::mem::size_of::<T>()) >= MIN_MAPPED
            && let Some(mapping) = mapped::Mapping::with_capacity(capacity)
        {
            return Self { storage: Storage::Mapped(mapping) };
        }
        Self { storage: Storage::Heap(Vec::with_capacity(capacity)) }
    }

    /// Number of items pushed.
    #[inline]
    pub fn len(&self) -> usize {
        match &self.storage {
            Storage::Heap(items) => items.len(),
            #[cfg(target_os = "linux")]
            Storage::Mapped(mapping) => mapping.as_slice().len(),
        }
    }

    /// Appends `items`.
    #[inline]
    pub fn extend_from_slice(&mut self, items: &[T]) {
        match &mut self.storage {
            Storage::Heap(heap) => heap.extend_from_slice(items),
            #[cfg(target_os = "linux")]
            Storage::Mapped(mapping) => {
                if !mapping.extend_from_slice(items) {
                    let mut heap = mapping.as_slice().to_vec();
                    heap.extend_from_slice(items);
                    self.storage = Storage::Heap(heap);
                }
            }
        }
    }

    /// The finished array.
    pub fn finish(self) -> PageArray<T> {
        match self.storage {
            Storage::Heap(mut items) => {
                items.shrink_to_fit();
                PageArray::new(items)
            }
            #[cfg(target_os = "linux")]
            Storage::Mapped(mapping) if std::mem::size_of_val(mapping.as_slice()) < MIN_MAPPED => {
                PageArray { storage: Storage::Heap(mapping.as_slice().to_vec()) }
            }
            #[cfg(target_os = "linux")]
            mapped @ Storage::Mapped(_) => PageArray { storage: mapped },
        }
    }
}

impl<T: Copy> Deref for PageArray<T> {
    type Target = [T];

    #[inline(always)]
    fn deref(&self) -> &[T] {
        match &self.storage {
            Storage::Heap(items) => items,
            #[cfg(target_os = "linux")]
            Storage::Mapped(mapping) => mapping.as_slice(),
        }
    }
}

impl<T: Copy> Clone for PageArray<T> {
    fn clone(&self) -> Self {
        Self::new(self.to_vec())
    }
}

impl<T: Copy + std::fmt::Debug> std::fmt::Debug for PageArray<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

#[cfg(target_os = "linux")]
mod mapped {
    use std::ptr::NonNull;

    use super::HUGE_PAGE;

    /// `len` values of `T` at the start of an anonymous private mapping of `bytes` bytes,
    /// with room for `capacity`.
    pub struct Mapping<T> {
        ptr: NonNull<T>,
        len: usize,
        capacity: usize,
        bytes: usize,
    }

    // SAFETY: the mapping is owned by this value alone and written only through `&mut
    // self`, so sharing or moving it across threads is as safe as for a `Vec<T>`.
    unsafe impl<T: Send> Send for Mapping<T> {}
    // SAFETY: as above; shared access is read-only.
    unsafe impl<T: Sync> Sync for Mapping<T> {}

    impl<T: Copy> Mapping<T> {
        /// A new mapping holding a copy of `items`; `None` when the system refuses one.
        pub fn copy_of(items: &[T]) -> Option<Self> {
            let mut mapping = Self::with_capacity(items.len())?;
            // SAFETY: the mapping has room for `items.len()` values of `T` at `ptr`, aligned
            // to 2 MiB (so to `T`), and does not overlap `items`.
            unsafe { std::ptr::copy_nonoverlapping(items.as_ptr(), mapping.ptr.as_ptr(), items.len()) };
            mapping.len = items.len();
            Some(mapping)
        }

        /// An empty mapping with room for `capacity` values; `None` when the system refuses
        /// one.
        pub fn with_capacity(capacity: usize) -> Option<Self> {
            let size = capacity.checked_mul(std::mem::size_of::<T>())?;
            if size == 0 || std::mem::align_of::<T>() > HUGE_PAGE {
                return None;
            }
            // Whole huge pages, plus one so a 2 MiB-aligned start can be chosen.
            let bytes = size.div_ceil(HUGE_PAGE).checked_add(1)?.checked_mul(HUGE_PAGE)?;
            // SAFETY: an anonymous private mapping at an address of the kernel's choosing
            // touches no existing memory; failure is reported as MAP_FAILED. No swap is
            // reserved for the part never written.
            let base = unsafe {
                libc::mmap(
                    std::ptr::null_mut(),
                    bytes,
                    libc::PROT_READ | libc::PROT_WRITE,
                    libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_NORESERVE,
                    -1,
                    0,
                )
            };
            if base == libc::MAP_FAILED {
                return None;
            }
            // Give the unaligned head back, so the array starts on a huge page boundary.
            let head = (HUGE_PAGE - base as usize % HUGE_PAGE) % HUGE_PAGE;
            let start = base.cast::<u8>().wrapping_add(head);
            let bytes = bytes - head;
            if head > 0 {
                // SAFETY: `base..base + head` is the start of the mapping made above, which
                // nothing refers to. A failed unmap only leaves those pages mapped.
                unsafe { libc::munmap(base, head) };
            }
            // SAFETY: `start..start + bytes` is mapped and ours. The advice is a hint: when
            // transparent huge pages are off it fails and the array keeps 4 KiB pages.
            unsafe { libc::madvise(start.cast(), bytes, libc::MADV_HUGEPAGE) };
            let ptr = NonNull::new(start.cast::<T>())?;
            Some(Self { ptr, len: 0, capacity, bytes })
        }

        /// Appends `items`; false (and nothing written) when they do not fit.
        #[inline]
        pub fn extend_from_slice(&mut self, items: &[T]) -> bool {
            if self.capacity - self.len < items.len() {
                return false;
            }
            // SAFETY: `len + items.len() <= capacity`, so the slots lie inside the mapping,
            // nothing refers to them yet, and they cannot overlap `items` (borrowed
            // elsewhere while `self` is borrowed mutably).
            unsafe { std::ptr::copy_nonoverlapping(items.as_ptr(), self.ptr.as_ptr().add(self.len), items.len()) };
            self.len += items.len();
            true
        }

        #[inline(always)]
        pub fn as_slice(&self) -> &[T] {
            // SAFETY: `ptr` points at `len` initialised values of `T` that live as long as
            // `self` and are written only through `&mut self`.
            unsafe { std::slice::from_raw_parts(self.ptr.as_ptr(), self.len) }
        }
    }

    impl<T> Drop for Mapping<T> {
        fn drop(&mut self) {
            // SAFETY: `ptr..ptr + bytes` is the part of the mapping `copy_of` kept, and no
            // reference into it outlives `self`. `T: Copy` has no destructor to run.
            unsafe { libc::munmap(self.ptr.as_ptr().cast(), self.bytes) };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_and_large_arrays_keep_their_contents() {
        for len in [0usize, 1, 1000, HUGE_PAGE / 8 + 5, MIN_MAPPED / 8 + 5] {
            let items: Vec<u64> = (0..len as u64).map(|i| i.wrapping_mul(0x9E37_79B9_7F4A_7C15)).collect();
            let array = PageArray::new(items.clone());
            assert_eq!(&array[..], &items[..]);
            assert_eq!(&array.clone()[..], &items[..]);
            assert_eq!(array.is_mapped(), cfg!(target_os = "linux") && len * 8 >= MIN_MAPPED);
            if array.is_mapped() {
                assert_eq!(array.as_ptr() as usize % HUGE_PAGE, 0);
            }
        }
    }

    #[test]
    fn buffers_keep_every_push_within_and_beyond_their_capacity() {
        let big = MIN_MAPPED / 8;
        for (capacity, len) in [(0usize, 3usize), (10, 10), (big, 1000), (big, big + 7), (2 * big, big + 7)] {
            let mut buffer = PageBuffer::with_capacity(capacity);
            for i in 0..len as u64 {
                buffer.extend_from_slice(&[i * 3]);
                assert_eq!(buffer.len(), i as usize + 1);
            }
            let array = buffer.finish();
            assert!(array.iter().copied().eq((0..len as u64).map(|i| i * 3)), "capacity {capacity}, {len} pushed");
            // Only arrays that end up large keep their mapping.
            assert!(!array.is_mapped() || len * 8 >= MIN_MAPPED);
        }
    }
}
