// fmt's compiled part (its src/format.cc), built here from the Debian package's own headers
// (fmt/format-inl.h) instead of linking libfmt.so, which Debian ships without a static archive
// and which needs the shared libstdc++: without it impactfe takes libstdc++ and libgcc from
// their archives, three shared libraries fewer to map and relocate on every run (issue 11,
// start-up). Only for the fmt version whose format.cc this mirrors (CMakeLists.txt defines
// IMPACTFE_COMPILE_FMT then, and links libfmt.so otherwise).
#include <fmt/format.h>

#if defined(IMPACTFE_COMPILE_FMT) && FMT_VERSION >= 90000 && FMT_VERSION < 100000
#include <fmt/format-inl.h>

FMT_BEGIN_NAMESPACE
namespace detail {

template FMT_API auto dragonbox::to_decimal(float x) noexcept -> dragonbox::decimal_fp<float>;
template FMT_API auto dragonbox::to_decimal(double x) noexcept -> dragonbox::decimal_fp<double>;

template FMT_API locale_ref::locale_ref(const std::locale& loc);
template FMT_API auto locale_ref::get<std::locale>() const -> std::locale;

// Explicit instantiations for char.
template FMT_API auto thousands_sep_impl(locale_ref) -> thousands_sep_result<char>;
template FMT_API auto decimal_point_impl(locale_ref) -> char;
template FMT_API void buffer<char>::append(const char*, const char*);
template FMT_API void vformat_to(buffer<char>&, string_view,
                                 basic_format_args<FMT_BUFFER_CONTEXT(char)>, locale_ref);

// Explicit instantiations for wchar_t.
template FMT_API auto thousands_sep_impl(locale_ref) -> thousands_sep_result<wchar_t>;
template FMT_API auto decimal_point_impl(locale_ref) -> wchar_t;
template FMT_API void buffer<wchar_t>::append(const wchar_t*, const wchar_t*);

}  // namespace detail
FMT_END_NAMESPACE
#endif
