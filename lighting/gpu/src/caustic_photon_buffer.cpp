#include "caustic_photon_buffer.hpp"

#include <limits>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting {

bool CausticPhotonBuffer::reserve(std::size_t photons) {
    const std::size_t bytes = photons * sizeof(CausticPhoton);
    if (buffer_ && buffer_.size() >= bytes) {
        return false;
    }
    if (photons > static_cast<std::size_t>(std::numeric_limits<GLint>::max())) {
        throw Error("CausticPass: too many caustic photons for one draw");
    }
    // Grown by half again so that a list growing a little each frame does not reallocate
    // every frame.
    buffer_ = gl::Buffer::create(bytes + bytes / 2);
    return true;
}

void CausticPhotonBuffer::write(std::size_t offset, std::span<const CausticPhoton> photons) {
    if (photons.empty()) {
        return;
    }
    buffer_.update(offset * sizeof(CausticPhoton), photons.size_bytes(), photons.data());
    bytes_uploaded_ += photons.size_bytes();
}

void CausticPhotonBuffer::upload(std::span<const CausticPhoton> photons) {
    pairs_.clear();
    firsts_.clear();
    counts_.clear();
    photon_count_ = 0;
    if (photons.empty()) {
        return;  // keep whatever buffer exists; allocate none
    }
    reserve(photons.size());
    write(0, photons);
    ++slices_uploaded_;
    firsts_.push_back(0);
    counts_.push_back(static_cast<GLsizei>(photons.size()));
    photon_count_ = static_cast<std::uint32_t>(photons.size());
}

bool CausticPhotonBuffer::same_layout(std::span<const CausticPair> pairs) const {
    if (pairs.size() != pairs_.size()) {
        return false;
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const CausticPair& pair = pairs[p];
        const PairRecord& record = pairs_[p];
        if (pair.generator != record.generator || pair.light != record.light ||
            pair.photons.photon_count() != record.photon_count ||
            pair.photons.slice_count() != record.slices.size()) {
            return false;
        }
    }
    return true;
}

void CausticPhotonBuffer::upload(std::span<const CausticPair> pairs) {
    const bool rewrite_all = !same_layout(pairs);
    if (rewrite_all) {
        pairs_.clear();
        std::size_t offset = 0;
        for (const CausticPair& pair : pairs) {
            PairRecord record{pair.generator, pair.light, pair.photons.photon_count(), {}};
            for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
                // A retrace count no list has: every slice is written below.
                record.slices.push_back({std::numeric_limits<std::uint64_t>::max(), 0, offset});
                offset += pair.photons.slice_size(k);
            }
            pairs_.push_back(std::move(record));
        }
        if (offset > 0) {
            reserve(offset);
        }
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
        const CausticPhotonList& list = pairs[p].photons;
        for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
            SliceRecord& record = pairs_[p].slices[k];
            const std::span<const CausticPhoton> photons = list.slice(k);
            if (!rewrite_all && record.retraces == list.slice_retraces(k) &&
                record.stored == photons.size()) {
                continue;
            }
            // A slice never stores more than its size (one photon per sample at most); the
            // check keeps a broken list from writing into its neighbour's range.
            if (photons.size() > list.slice_size(k)) {
                throw Error("CausticPass: a caustic slice holds more photons than its size");
            }
            write(record.offset, photons);
            record.retraces = list.slice_retraces(k);
            record.stored = photons.size();
            ++slices_uploaded_;
        }
    }
    rebuild_ranges();
}

void CausticPhotonBuffer::rebuild_ranges() {
    firsts_.clear();
    counts_.clear();
    photon_count_ = 0;
    for (const PairRecord& pair : pairs_) {
        for (const SliceRecord& slice : pair.slices) {
            if (slice.stored == 0) {
                continue;
            }
            // Adjacent ranges merge: fewer draws when slices are full.
            if (!counts_.empty() &&
                static_cast<std::size_t>(firsts_.back() + counts_.back()) == slice.offset) {
                counts_.back() += static_cast<GLsizei>(slice.stored);
            } else {
                firsts_.push_back(static_cast<GLint>(slice.offset));
                counts_.push_back(static_cast<GLsizei>(slice.stored));
            }
            photon_count_ += static_cast<std::uint32_t>(slice.stored);
        }
    }
}

}  // namespace luxel::lighting
