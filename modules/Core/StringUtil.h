#ifndef bender_StringUtil_h
#define bender_StringUtil_h

// The small string helpers every layer needs, written once: case folding for file extensions
// and keywords, the extension of a path, the display name used to prefix messages and
// the text of a point in them, a count with its noun, trimming.
// ASCII only (file extensions, keywords, device names); no locale is consulted.

#include <array>
#include <string>
#include <string_view>

namespace bender
{

/// text with A-Z folded to a-z; other bytes unchanged.
std::string ToLower(std::string_view text);

/// True when text and other are equal after ToLower.
bool EqualsIgnoreCase(std::string_view text, std::string_view other);

/// True when text starts / ends with affix (case-sensitive).
bool StartsWith(std::string_view text, std::string_view prefix);
bool EndsWith(std::string_view text, std::string_view suffix);

/// The extension of path's last component in lower case, with its dot (".stl"); empty when
/// there is none. "a.nii.gz" gives ".gz" (see LowerDoubleExtension).
std::string LowerExtension(const std::string& path);

/// Like LowerExtension, but takes the two-part compressed extensions whole (".nii.gz").
std::string LowerDoubleExtension(const std::string& path);

/// The last path component ("aneurysm.stl" for "/data/aneurysm.stl"); the whole path when it
/// has none. Used to prefix one-line messages.
std::string DisplayName(const std::string& path);

/// How messages name a point: "(x, y, z)" with 4 significant digits; a coordinate within a
/// millionth of the largest one's magnitude of 0 is written 0.
std::string FormatPoint(const std::array<double, 3>& p);

/// How messages name a number: `digits` significant digits ("26", "1.2", "0.0125").
std::string FormatNumber(double value, int digits = 3);

/// "1 warp", "2 warps", "0 warps": a count with its noun (regular English plural, "s" added).
std::string CountOf(std::size_t count, std::string_view noun);

/// text without leading and trailing blanks (space, tab, CR, LF, FF, VT).
std::string_view Trim(std::string_view text);

} // namespace bender

#endif
