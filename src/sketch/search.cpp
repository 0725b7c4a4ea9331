// Best-first search over rule applications (ShipShape §7.3, Fig. 7.4–7.5).
//
// Each node holds a candidate; its children are the outputs of every rule not yet considered on
// its branch (endpoint snapping stays available until both endpoints are fixed), plus, per rule
// that proposed something, a "declined" child (the unmodified path with likelihood 1 − max of that
// rule's proposals). A node's score is the chained likelihood L = 1 − Π(1 − L_k) of Eq. 7.1. Nodes
// are expanded in order of score (ties: creation order, so the search is deterministic). A node
// none of whose remaining rules proposes anything is a leaf and joins the suggestion set Q if no
// suggestion has the same geometry. Before a node is expanded its properties (the keys of its
// relations and its declined rules) are compared with each suggestion's: if all are found in one,
// its subtree is skipped (Fig. 7.5).
//
// Deviation: after `max_expansions` expansions, remaining nodes are completed greedily (always
// the best child) instead of branching, which bounds the time for crowded drawings.

#include <algorithm>
#include <cstdint>
#include <queue>
#include <set>
#include <string>

#include "exemplar/sketch/beautify.hpp"

namespace exemplar::sketch {

namespace {

struct Node {
    Candidate candidate;
    double score = 0.0;
    std::uint32_t considered = 0;  // bit r: rule r applied or declined on this branch
    std::uint64_t order = 0;
};

struct ByScore {
    bool operator()(const Node& a, const Node& b) const {
        if (a.score != b.score) return a.score < b.score;
        return a.order > b.order;
    }
};

std::set<std::string> properties(const Candidate& c) {
    std::set<std::string> keys;
    for (const Relation& r : c.relations) keys.insert(r.key);
    for (const std::string& d : c.declined) keys.insert("!" + d);
    return keys;
}

class Search {
public:
    Search(const RuleContext& context, int max_results)
        : context_(context), rules_(make_rules()), max_results_(max_results) {}

    std::vector<std::pair<Candidate, double>> run(const Candidate& input) {
        push({input, 0.0, 0, 0});
        int expansions = 0;
        while (!queue_.empty() && static_cast<int>(found_.size()) < max_results_) {
            Node node = queue_.top();
            queue_.pop();
            if (pruned(node)) continue;
            if (expansions >= context_.options->max_expansions) {
                finish(complete_greedily(std::move(node)));
                continue;
            }
            ++expansions;
            std::vector<Node> children = expand(node);
            if (children.empty()) {
                finish(std::move(node));
                continue;
            }
            for (Node& child : children) push(std::move(child));
        }
        std::vector<std::pair<Candidate, double>> out;
        for (std::size_t i = 0; i < found_.size(); ++i) {
            out.emplace_back(std::move(found_[i].candidate), found_[i].score);
        }
        return out;
    }

private:
    void push(Node node) {
        node.order = next_order_++;
        queue_.push(std::move(node));
    }

    // Children of a node: rule outputs and per-rule declined copies.
    std::vector<Node> expand(const Node& node) {
        std::vector<Node> children;
        for (std::size_t r = 0; r < rules_.size(); ++r) {
            const std::uint32_t bit = 1u << r;
            if (node.considered & bit) continue;
            std::vector<RuleOutput> outputs = rules_[r]->apply(node.candidate, context_);
            if (outputs.empty()) continue;
            double best = 0.0;
            const std::uint32_t applied =
                rules_[r]->repeatable() ? node.considered : node.considered | bit;
            for (RuleOutput& o : outputs) {
                best = std::max(best, o.likelihood);
                children.push_back(
                    {std::move(o.candidate), chain(node.score, o.likelihood), applied, 0});
            }
            Node declined{node.candidate, chain(node.score, 1.0 - best), node.considered | bit, 0};
            declined.candidate.declined.emplace_back(rules_[r]->name());
            children.push_back(std::move(declined));
        }
        return children;
    }

    // Follows the best child until a leaf.
    Node complete_greedily(Node node) {
        while (true) {
            std::vector<Node> children = expand(node);
            if (children.empty()) return node;
            auto best =
                std::max_element(children.begin(), children.end(),
                                 [](const Node& a, const Node& b) { return ByScore{}(a, b); });
            node = std::move(*best);
        }
    }

    static double chain(double score, double likelihood) {
        return 1.0 - (1.0 - score) * (1.0 - std::clamp(likelihood, 0.0, 1.0));
    }

    bool pruned(const Node& node) const {
        if (found_keys_.empty()) return false;
        const std::set<std::string> mine = properties(node.candidate);
        for (const std::set<std::string>& keys : found_keys_) {
            if (std::includes(keys.begin(), keys.end(), mine.begin(), mine.end())) return true;
        }
        return false;
    }

    void finish(Node node) {
        const int n = 16;
        const std::vector<Vec2> mine = sample_path(node.candidate.path, n);
        const double limit = context_.units(context_.options->duplicate_px);
        for (const std::vector<Vec2>& other : found_samples_) {
            if (max_pointwise_distance(mine, other) < limit) return;
        }
        found_samples_.push_back(mine);
        found_keys_.push_back(properties(node.candidate));
        found_.push_back(std::move(node));
    }

    const RuleContext& context_;
    std::vector<std::unique_ptr<Rule>> rules_;
    int max_results_;
    std::priority_queue<Node, std::vector<Node>, ByScore> queue_;
    std::uint64_t next_order_ = 0;
    std::vector<Node> found_;
    std::vector<std::set<std::string>> found_keys_;
    std::vector<std::vector<Vec2>> found_samples_;
};

}  // namespace

std::vector<std::pair<Candidate, double>> search(const Candidate& input, const RuleContext& context,
                                                 int max_results) {
    return Search(context, max_results).run(input);
}

}  // namespace exemplar::sketch
