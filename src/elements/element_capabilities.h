#pragma once
/// The optional interfaces an element may implement beside Element, which the drivers reach
/// with dynamic_cast (kept out of element.h, which much of the program includes). Every such
/// interface is listed here. An element adapter (assembly/element_adapters.h) implements each
/// listed interface by forwarding it to the element it wraps, and asserts so at compile time:
/// an adapter cannot hide what an element can do.
#include <type_traits>

#include "elements/connectivity.h"
#include "elements/penetration_check.h"

namespace impactfe {

template <class... Interfaces>
struct InterfaceList {};

/// Every optional element interface.
using ElementCapabilities = InterfaceList<PenetrationCheck, ConnectivityUpdate>;

/// True when T implements every interface of the list.
template <class T, class... Interfaces>
constexpr bool implements_all(InterfaceList<Interfaces...>) {
  return (std::is_base_of_v<Interfaces, T> && ...);
}

}  // namespace impactfe
