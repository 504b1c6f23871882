// Strong id types and vectors indexed by them, so a ContourId cannot be passed as a NodeId.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace cutroute {

template <class Tag, class Rep = std::int32_t>
class Id {
 public:
  using rep_type = Rep;
  constexpr Id() = default;
  constexpr explicit Id(Rep v) : v_(v) {}
  constexpr Rep value() const { return v_; }
  constexpr std::size_t index() const { return static_cast<std::size_t>(v_); }
  constexpr bool valid() const { return v_ >= 0; }
  friend constexpr auto operator<=>(Id, Id) = default;

 private:
  Rep v_ = -1;
};

// A std::vector whose subscript takes the id type it is indexed by.
template <class IdT, class T>
class IdVector : public std::vector<T> {
 public:
  using std::vector<T>::vector;
  T& operator[](IdT id) { return std::vector<T>::operator[](id.index()); }
  const T& operator[](IdT id) const { return std::vector<T>::operator[](id.index()); }
  IdT next_id() const { return IdT(static_cast<typename IdT::rep_type>(this->size())); }
};

}  // namespace cutroute

template <class Tag, class Rep>
struct std::hash<cutroute::Id<Tag, Rep>> {
  std::size_t operator()(cutroute::Id<Tag, Rep> id) const noexcept { return std::hash<Rep>{}(id.value()); }
};
