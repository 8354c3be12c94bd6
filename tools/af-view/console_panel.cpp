#include "console_panel.h"

#include "console_completion.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>

namespace af::view {

namespace {

constexpr std::size_t kMaxLines = 4000;

// How many leading characters every candidate shares with the first, ignoring case.
std::size_t commonPrefix(const std::vector<std::string>& words) {
    std::size_t n = words.front().size();
    for (const std::string& w : words) {
        std::size_t i = 0;
        while (i < n && i < w.size() && std::tolower(static_cast<unsigned char>(w[i])) == std::tolower(static_cast<unsigned char>(words.front()[i]))) ++i;
        n = i;
    }
    return n;
}

}  // namespace

void ConsolePanel::add(std::string_view text, bool error) {
    lines_.push_back({std::string(text), error});
    while (lines_.size() > kMaxLines) lines_.pop_front();
    scrollToEnd_ = true;
}

int ConsolePanel::onInput(ImGuiInputTextCallbackData& data) {
    if (data.EventFlag == ImGuiInputTextFlags_CallbackHistory && !history_.empty()) {
        const int last = int(history_.size()) - 1;
        if (data.EventKey == ImGuiKey_UpArrow) historyPosition_ = historyPosition_ < 0 ? last : std::max(0, historyPosition_ - 1);
        else if (data.EventKey == ImGuiKey_DownArrow && historyPosition_ >= 0) historyPosition_ = historyPosition_ < last ? historyPosition_ + 1 : -1;
        data.DeleteChars(0, data.BufTextLen);
        if (historyPosition_ >= 0) data.InsertChars(0, history_[std::size_t(historyPosition_)].c_str());
    } else if (data.EventFlag == ImGuiInputTextFlags_CallbackCompletion && console_ && session_) {
        const std::string before(data.Buf, std::size_t(data.CursorPos));
        const std::vector<std::string> candidates = console::completeConsoleLine(*console_, *session_, before);
        if (candidates.empty()) return 0;
        const std::size_t wordStart = before.find_last_of(" \t\"") == std::string::npos ? 0 : before.find_last_of(" \t\"") + 1;
        const std::size_t keep = candidates.size() == 1 ? candidates.front().size() : commonPrefix(candidates);
        data.DeleteChars(int(wordStart), data.CursorPos - int(wordStart));
        data.InsertChars(data.CursorPos, (candidates.front().substr(0, keep) + (candidates.size() == 1 ? " " : "")).c_str());
        if (candidates.size() > 1) {
            std::string all;
            for (const std::string& c : candidates) all += c + "  ";
            add(all, false);
        }
    }
    return 0;
}

void ConsolePanel::draw(console::CommandSystem& console, const console::Session& session, float x, float y, float width, float height) {
    console_ = &console;
    session_ = &session;
    ImGui::SetNextWindowPos({x, y}, ImGuiCond_Always);
    ImGui::SetNextWindowSize({width, height}, ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Console", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    const float inputHeight = ImGui::GetFrameHeightWithSpacing();
    ImGui::BeginChild("output", {0, -inputHeight}, false, ImGuiWindowFlags_HorizontalScrollbar);
    for (const Line& line : lines_) {
        if (line.error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.40f, 1.0f));
        ImGui::TextUnformatted(line.text.c_str());
        if (line.error) ImGui::PopStyleColor();
    }
    if (scrollToEnd_) ImGui::SetScrollHereY(1.0f);
    scrollToEnd_ = false;
    ImGui::EndChild();

    ImGui::PushItemWidth(-1);
    const ImGuiInputTextFlags flags = ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CallbackHistory | ImGuiInputTextFlags_CallbackCompletion;
    const auto callback = [](ImGuiInputTextCallbackData* data) { return static_cast<ConsolePanel*>(data->UserData)->onInput(*data); };
    if (ImGui::InputText("##input", &input_, flags, callback, this)) {
        if (!input_.empty()) {
            add("] " + input_, false);
            if (history_.empty() || history_.back() != input_) history_.push_back(input_);
            const std::string line = input_;
            input_.clear();
            console.execute(line);
        }
        historyPosition_ = -1;
        refocus_ = true;
    }
    // The input line keeps the keyboard: after a line is run, and whenever the panel is clicked
    // and nothing else in it is being edited.
    ImGui::SetItemDefaultFocus();
    if (refocus_ || (ImGui::IsWindowFocused(ImGuiFocusedFlags_RootAndChildWindows) && !ImGui::IsAnyItemActive() && !ImGui::IsMouseDown(0)))
        ImGui::SetKeyboardFocusHere(-1);
    refocus_ = false;
    ImGui::PopItemWidth();
    ImGui::End();
    console_ = nullptr;
    session_ = nullptr;
}

}  // namespace af::view
