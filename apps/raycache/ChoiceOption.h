#pragma once
// Options whose value is one of a module's names (a pipeline, a technique, a
// tile balance...): CLI11 checks the name and converts it to the module's
// enum while it parses, from that module's own values and name function, so
// the options structs hold typed values and nothing after main() reads the
// name again.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <optional>
#include <ranges>
#include <string>
#include <utility>
#include <vector>

namespace raycache {

// A CLI11 transform accepting exactly the names `name(v)` of the `values`
// (one enum's, in the order a message lists them) and handing the option the
// value each stands for. Any other word fails as "must be a, b or c (got
// 'x')", which CLI11 prefixes with the option's flag: one line.
template <std::ranges::input_range Values, class Name>
CLI::Validator choiceOf(const Values& values, Name name) {
    using Value = std::ranges::range_value_t<Values>;
    std::vector<std::pair<std::string, Value>> choices;
    for (const Value value : values) choices.emplace_back(name(value), value);
    std::string list, braces;
    for (std::size_t i = 0; i < choices.size(); ++i) {
        list += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i].first;
        braces += (i == 0 ? "{" : ",") + choices[i].first;
    }
    braces += "}";
    return CLI::Validator(
        [choices, list](std::string& input) -> std::string {
            for (const auto& [choiceName, value] : choices) {
                if (input != choiceName) continue;
                // CLI11 converts an enum (or bool) option from its integer.
                input = std::to_string(static_cast<long long>(value));
                return {};
            }
            return "must be " + list + " (got '" + input + "')";
        },
        braces);
}

// Adds `flag`, which sets `target` to one of `values` by name; the help
// shows the names and the target's starting value as the default.
template <class Value, class Values, class Name>
CLI::Option* addChoiceOption(CLI::App& command, const std::string& flag, Value& target, const Values& values, Name name,
                             const std::string& description) {
    return command.add_option(flag, target, description)
        ->type_name("TEXT")
        ->transform(choiceOf(values, name))
        ->default_str(name(target));
}

// The same for a value that has no default here (the scene's, a material's...).
template <class Value, class Values, class Name>
CLI::Option* addChoiceOption(CLI::App& command, const std::string& flag, std::optional<Value>& target,
                             const Values& values, Name name, const std::string& description) {
    return command.add_option(flag, target, description)->type_name("TEXT")->transform(choiceOf(values, name));
}

}  // namespace raycache
