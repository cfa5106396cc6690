// "Did you mean": the candidate nearest to a misspelt name, by edit distance
// (insertions, deletions, substitutions and swaps of neighbours each count 1).
#pragma once
#include <string>
#include <vector>

namespace mfsd {

// Optimal string alignment distance between a and b.
size_t edit_distance(const std::string& a, const std::string& b);

// The candidate nearest to `name` when it is close enough to be a typo (at
// most 1 edit for names of 3-4 characters, 2 up to 8, 3 beyond; none for
// names of 1-2 characters), else "".
// Ties go to the first candidate.
std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" for nearest_name's answer, or "" when there is none.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates);

}  // namespace mfsd
