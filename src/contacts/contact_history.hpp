// Per-contact data carried from one step to the next while the contact lasts
// (a tangential spring, a bond's age): one value per contact of a
// ContactList, in the list's order, kept across the list's rebuilds and
// keyed by particle ids, so that it survives particles being inserted,
// removed or reordered (LAMMPS's fix neigh/history keeps its shear history
// by atom tags in the same way).
//
// After every ContactList::update, call update(list, ids): values()[m]
// belongs to the contact (i, partners()[m]) of row i; it holds the value
// the same pair of ids had at the last call if they were in contact then,
// else T{}. Steady state (no more contacts than before) allocates nothing.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hgridlab/base/error.hpp"
#include "hgridlab/base/radix.hpp"
#include "hgridlab/contacts/contact_list.hpp"

namespace hgrid {

template <class T>
class ContactHistory {
 public:
  /// ids[i]: particle i's id (unique: two particles with one id would share
  /// their contacts' values); empty: the index is the id.
  /// Throws InputError if ids has another length than the list's particles
  /// (the history is then left as it was).
  template <int D>
  void update(const ContactList<D>& list, std::span<const std::uint32_t> ids = {}) {
    const std::size_t n = list.size();
    if (!ids.empty() && ids.size() != n)
      throw InputError("ids", "must hold one id per particle (" + std::to_string(n) + "), got " +
                                  std::to_string(ids.size()));
    commit();  // the values written since the last update, in the order of its sorted keys
    const auto start = list.start();
    const auto partners = list.partners();
    const std::size_t M = partners.size();
    // The contacts' id keys (smaller id high), in the list's order; sorted
    // already when the ids increase with the index (or are the index).
    bool monotone = true;
    for (std::size_t i = 1; i < ids.size() && monotone; ++i) monotone = ids[i - 1] < ids[i];
    key_.resize(M);
    for (std::size_t i = 0; i + 1 < start.size(); ++i)
      for (std::uint32_t m = start[i]; m < start[i + 1]; ++m) {
        const std::uint32_t j = partners[m];
        const std::uint64_t a = ids.empty() ? i : ids[i], b = ids.empty() ? j : ids[j];
        key_[m] = a < b ? (a << 32) | b : (b << 32) | a;
      }
    // order_[r]: the contact of the r-th smallest key.
    order_.resize(M);
    for (std::size_t m = 0; m < M; ++m) order_[m] = static_cast<std::uint32_t>(m);
    if (!monotone) {
      skey_.assign(key_.begin(), key_.end());
      tkey_.resize(M);
      tid_.resize(M);
      detail::radix_sort_pairs(skey_.data(), order_.data(), tkey_.data(), tid_.data(), M, 64);
    }
    // Merge with the last call's sorted keys: carried values, else T{}.
    next_.resize(M);
    carried_ = 0;
    std::size_t p = 0;
    for (std::size_t r = 0; r < M; ++r) {
      const std::uint32_t m = order_[r];
      const std::uint64_t k = key_[m];
      while (p < keys_.size() && keys_[p] < k) ++p;
      if (p < keys_.size() && keys_[p] == k) {
        next_[m] = sorted_values_[p];
        ++carried_;
      } else {
        next_[m] = T{};
      }
    }
    values_.swap(next_);
    keys_.resize(M);
    for (std::size_t r = 0; r < M; ++r) keys_[r] = key_[order_[r]];
    sorted_dirty_ = true;
  }

  /// One value per contact of the list's last update, in its order; write
  /// the new values here before the next update.
  std::span<T> values() {
    sorted_dirty_ = true;
    return {values_.data(), values_.size()};
  }
  std::span<const T> values() const { return {values_.data(), values_.size()}; }
  /// Contacts whose value was carried from the last update.
  std::size_t carried() const { return carried_; }

 private:
  /// Takes the values written since the last update as the history the
  /// next update carries.
  void commit() {
    if (!sorted_dirty_) return;
    sorted_values_.resize(values_.size());
    for (std::size_t r = 0; r < keys_.size(); ++r) sorted_values_[r] = values_[order_[r]];
    sorted_dirty_ = false;
  }

  std::vector<std::uint64_t> key_, skey_, tkey_, keys_;  // keys_: the last update's contacts' keys, sorted
  std::vector<std::uint32_t> order_, tid_;
  std::vector<T> values_, next_, sorted_values_;  // sorted_values_: values_ in the order of keys_
  std::size_t carried_ = 0;
  bool sorted_dirty_ = false;
};

}  // namespace hgrid
