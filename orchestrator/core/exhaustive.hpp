#pragma once
// Exhaustive dispatch over a closed set (a std::variant): the last branch of an
// `if constexpr` chain inside std::visit is
//     else static_assert(kUnhandled<T>, "...");
// so that an alternative added to the variant without its behaviour does not compile
// (instead of falling into another alternative's branch or a silent default).
namespace orch {

template <class...>
inline constexpr bool kUnhandled = false;

}  // namespace orch
