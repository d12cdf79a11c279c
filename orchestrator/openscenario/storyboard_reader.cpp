// Storyboard: Init, Stories, Acts, ManeuverGroups, Maneuvers, Events, Actions and the
// triggers; entity and storyboard element references are checked here, at load.
#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "core/suggest.hpp"
#include "openscenario/element_path.hpp"
#include "openscenario/reader_context.hpp"

namespace orch::openscenario::reading {
namespace {

void position_entities(const Position& p, std::vector<std::string>& names) {
  std::visit(
      [&](const auto& kind) {
        using T = std::decay_t<decltype(kind)>;
        if constexpr (requires { kind.entity; }) names.push_back(kind.entity);
        if constexpr (std::is_same_v<T, position::RoutePosition>) {
          if (const auto* current = std::get_if<position::InRouteFromEntity>(&kind.in_route))
            names.push_back(current->entity);
          for (const position::RouteWaypoint& w : kind.route->waypoints) position_entities(w.position, names);
        }
        if constexpr (std::is_same_v<T, position::TrajectoryPosition>)
          for (const Position& vertex : kind.path->positions()) position_entities(vertex, names);
      },
      p);
}

// Entities an action refers to besides its actors: by member, so a new action's references
// are checked without an entry here (`entity`, `relative_to`, positions, waypoints, vertices).
std::vector<std::string> referenced_entities(const PrivateAction& action) {
  std::vector<std::string> names;
  std::visit(
      [&](const auto& a) {
        using T = std::decay_t<decltype(a)>;
        if constexpr (requires { a.position; }) position_entities(a.position, names);
        if constexpr (requires { a.master_position; }) position_entities(a.master_position, names);
        if constexpr (requires { a.entity; }) names.push_back(a.entity);
        if constexpr (requires { a.relative_to; })
          if (a.relative_to) names.push_back(*a.relative_to);
        if constexpr (std::is_same_v<T, SpeedAction>)
          if (const auto* r = std::get_if<RelativeTargetSpeed>(&a.target)) names.push_back(r->entity);
        if constexpr (std::is_same_v<T, AssignRouteAction>)
          for (const Position& p : a.waypoints) position_entities(p, names);
        if constexpr (std::is_same_v<T, TrafficAreaAction>)
          for (const Position& p : a.polygon) position_entities(p, names);
        if constexpr (std::is_same_v<T, FollowTrajectoryAction>) {
          if (const auto* polyline = std::get_if<PolylineShape>(&a.trajectory.shape))
            for (const TrajectoryVertex& v : polyline->vertices) position_entities(v.position, names);
          else if (const auto* nurbs = std::get_if<NurbsShape>(&a.trajectory.shape))
            for (const NurbsControlPoint& c : nurbs->points) position_entities(c.position, names);
          else if (const auto* spline = std::get_if<ClothoidSplineShape>(&a.trajectory.shape)) {
            for (const ClothoidSplineSegment& segment : spline->segments)
              if (segment.start) position_entities(*segment.start, names);
          } else {
            position_entities(std::get<ClothoidShape>(a.trajectory.shape).start, names);
          }
        }
      },
      action);
  return names;
}

class StoryboardReader {
 public:
  StoryboardReader(const Scenario& scenario, Context& context) : scenario_(scenario), context_(context) {
    for (const Entity& e : scenario.entities) entity_names_.push_back(e.name);
  }

  Storyboard read(Element& storyboard) {
    Storyboard board;
    Element init = storyboard.child("Init");
    Element actions = init.child("Actions");
    init.finish();
    for (Element p : actions.children("Private")) {
      const std::string entity = entity_ref(p, "entityRef");
      for (Element a : p.children("PrivateAction")) {
        const Place place = a.place();
        board.init.push_back({entity, read_private_action(a, context_), place});
        check_action_references(board.init.back().action, place);
      }
      p.finish();
    }
    for (Element g : actions.children("GlobalAction")) {
      const Place place = g.place();
      board.init.push_back({"", read_global_action(g, context_), place});
      check_action_references(board.init.back().action, place);
    }
    for (Element u : actions.children("UserDefinedAction")) {  // no actors, like a global action
      const Place place = u.place();
      board.init.push_back({"", read_user_defined_action(u, context_), place});
    }
    actions.finish();
    order_init(board.init);
    for (Element story : storyboard.children("Story")) board.stories.push_back(read_story(story));
    Element stop = storyboard.child("StopTrigger");
    board.stop_trigger = read_trigger(stop, context_);
    storyboard.finish();
    check_state_references(board);
    return board;
  }

 private:
  static bool has_entity_condition(const std::optional<Trigger>& t) {
    if (!t) return false;
    for (const auto& group : t->groups)
      for (const Condition& c : group)
        if (std::holds_alternative<ByEntityCondition>(c.kind)) return true;
    return false;
  }

  std::string entity_ref(Element& e, const char* attribute) {
    const std::string name = e.text(attribute);
    if (scenario_.entity(name) == nullptr)
      e.fail_attribute(attribute, fmt::format("no entity named \"{}\"{}", name, did_you_mean(name, entity_names_)));
    return name;
  }

  // Names a storyboard element: its key is the path of names from its Story down ("s::a::g"),
  // unique however often a name repeats in other parents (the standard allows that). Siblings
  // of one type and name break the standard's rule; they run as distinct elements (as in
  // esmini) with a warning, and a reference to them is ambiguous (resolve_reference).
  std::string declare(const std::string& type, Element& e, const std::string& name) {
    std::vector<std::string> path = path_;
    path.push_back(name);
    std::string key = join_path(path);
    if (!keys_.insert({type, key}).second) {
      context_.warnings.warning(e.source().where(e.node(), "name"),
                                fmt::format("a second {} named \"{}\" in the same parent: the standard wants the names "
                                            "of siblings unique; both run, a reference to them is ambiguous",
                                            type, name));
      for (int n = 2;; ++n)
        if (keys_.insert({type, fmt::format("{}#{}", key, n)}).second) {
          key = fmt::format("{}#{}", key, n);
          break;
        }
    }
    declared_[type].push_back({std::move(path), key, e.place().line});
    return key;
  }

  // Holds `name` on the path of the elements read inside it.
  struct Nested {
    Nested(std::vector<std::string>& path, const std::string& name) : path_(path) { path_.push_back(name); }
    ~Nested() { path_.pop_back(); }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;
    std::vector<std::string>& path_;
  };

  // An empty trigger (no ConditionGroup) is read as none: the standard keeps empty triggers
  // only "for the sake of downward compatibility" with 1.0, where an Act had to have a
  // StartTrigger (docs/openscenario.md, "Empty triggers"). So an empty StartTrigger starts its
  // element as an absent one does, an empty StopTrigger never stops it, as in esmini.
  std::optional<Trigger> trigger(Element& owner, const char* name) {
    auto t = owner.optional_child(name);
    if (!t) return std::nullopt;
    Trigger read = read_trigger(*t, context_);
    if (read.groups.empty()) return std::nullopt;
    return read;
  }

  Story read_story(Element& outer) {
    Story story;
    story.name = outer.text("name");
    story.key = declare("story", outer, story.name);
    const Nested inside(path_, story.name);
    Element e = open_scope(outer, context_, story.name);  // its parameters: "<story>/<name>"
    for (Element act : e.children("Act")) story.acts.push_back(read_act(act));
    if (story.acts.empty()) e.fail("a Story needs at least one Act");
    e.finish();
    return story;
  }

  Act read_act(Element& e) {
    Act act;
    act.name = e.text("name");
    act.key = declare("act", e, act.name);
    const Nested inside(path_, act.name);
    act_key_ = act.key;
    std::vector<Element> selecting_alone;  // Actors that name no entity and select the triggering ones
    for (Element g : e.children("ManeuverGroup")) {
      act.groups.push_back(read_group(g));
      if (act.groups.back().select_triggering_entities && act.groups.back().actors.empty())
        selecting_alone.push_back(Element(g.source(), g.node().child("Actors"), g.scope()));
    }
    if (act.groups.empty()) e.fail("an Act needs at least one ManeuverGroup");
    const bool has_start_trigger = static_cast<bool>(e.node().child("StartTrigger"));
    act.start_trigger = trigger(e, "StartTrigger");
    // A group whose only actors are the triggering entities needs an Act started by entities.
    if (!selecting_alone.empty() && !has_entity_condition(act.start_trigger))
      selecting_alone.front().fail_attribute(
          "selectTriggeringEntities",
          "the actors are the entities that triggered the Act's StartTrigger, which has no ByEntityCondition: "
          "the ManeuverGroup would have no actors (name them by EntityRef)");
    // Optional since 1.1: an Act without one starts with its Story (the runtime's fires()).
    if (!has_start_trigger && scenario_.rev_minor == 0) e.fail("an Act needs a StartTrigger (OpenSCENARIO 1.0)");
    act.stop_trigger = trigger(e, "StopTrigger");
    e.finish();
    return act;
  }

  ManeuverGroup read_group(Element& e) {
    ManeuverGroup g;
    g.name = e.text("name");
    g.key = declare("maneuverGroup", e, g.name);
    const Nested inside(path_, g.name);
    g.maximum_execution_count = e.integer("maximumExecutionCount");
    if (g.maximum_execution_count < 1) e.fail_attribute("maximumExecutionCount", "must be at least 1");
    Element actors = e.child("Actors");
    // The standard: "Indicates whether the triggering entities are considered actors": the
    // entities that made the enclosing Act's StartTrigger fire join the named ones when the
    // Act starts (storyboard_runtime.cpp; docs/openscenario.md "Actors").
    g.select_triggering_entities = actors.boolean("selectTriggeringEntities");
    for (Element ref : actors.children("EntityRef")) {
      g.actors.push_back(entity_ref(ref, "entityRef"));
      ref.finish();
    }
    actors.finish();
    // Maneuvers inline and from a ManeuverCatalog, in the order written.
    selecting_act_ = g.select_triggering_entities ? act_key_ : std::string();
    for (const pugi::xml_node n : e.node().children()) {
      if (n.type() != pugi::node_element) continue;
      Element m(e.source(), n, e.scope());
      if (m.name() == "Maneuver") {
        g.maneuvers.push_back(read_maneuver(m, g.actors, true));
      } else if (m.name() == "CatalogReference") {
        Element entry = context_.resolve(m, {"Maneuver"});
        g.maneuvers.push_back(read_maneuver(entry, g.actors, false));  // resolve() read its declarations
        catalog_maneuvers_.insert(g.maneuvers.back().key);
      }
    }
    selecting_act_.clear();
    e.ignore_children({"Maneuver", "CatalogReference"});
    e.finish();
    return g;
  }

  Maneuver read_maneuver(Element& outer, const std::vector<std::string>& actors, bool own_declarations) {
    Maneuver m;
    m.name = outer.text("name");
    m.key = declare("maneuver", outer, m.name);
    const Nested inside(path_, m.name);
    // Its parameters: "<maneuver>/<name>".
    Element e = own_declarations ? open_scope(outer, context_, m.name) : outer;
    for (Element ev : e.children("Event")) m.events.push_back(read_event(ev, actors));
    if (m.events.empty()) e.fail("a Maneuver needs at least one Event");
    e.finish();
    return m;
  }

  Event read_event(Element& e, const std::vector<std::string>& actors) {
    Event ev;
    ev.name = e.text("name");
    ev.key = declare("event", e, ev.name);
    const Nested inside(path_, ev.name);
    ev.priority = e.choice<Priority>("priority", {{"overwrite", Priority::Overwrite},
                                                  {"override", Priority::Overwrite},
                                                  {"skip", Priority::Skip},
                                                  {"parallel", Priority::Parallel}});
    ev.maximum_execution_count = e.optional_integer("maximumExecutionCount").value_or(1);
    if (ev.maximum_execution_count < 1) e.fail_attribute("maximumExecutionCount", "must be at least 1");
    for (Element a : e.children("Action")) {
      Action action;
      action.name = a.text("name");
      action.key = declare("action", a, action.name);
      action.place = a.place();
      Element kind = a.one_of({"PrivateAction", "GlobalAction", "UserDefinedAction"});
      if (kind.name() == "UserDefinedAction") {
        action.action = read_user_defined_action(kind, context_);  // no actors, like a global action
      } else if (kind.name() == "GlobalAction") {
        action.action = read_global_action(kind, context_);
      } else {
        if (actors.empty() && selecting_act_.empty()) a.fail("a private action needs actors in its ManeuverGroup");
        action.actors = actors;  // with selectTriggeringEntities the runtime adds the triggering ones
        action.action = read_private_action(kind, context_);
      }
      check_action_references(action.action, action.place);
      a.finish();
      ev.actions.push_back(std::move(action));
    }
    if (ev.actions.empty()) e.fail("an Event needs at least one Action");
    ev.start_trigger = trigger(e, "StartTrigger");
    e.finish();
    return ev;
  }

  // Every StoryboardElementStateCondition names one element of its type: by its name, or by
  // the end of its path of names ("event::action") where the name alone is not unique.
  //
  // A Maneuver from a catalog can name its own elements only by their names: it cannot know
  // where it will be instantiated, and it may be instantiated more than once (esmini's
  // synchronize.xosc uses one twice). A reference written in such a Maneuver (`scope`, its
  // path of names) that names several elements is resolved within that instance first: the
  // element the standard's unique-reference rule means is the one of this instance (where
  // the reference names exactly one); else it is ambiguous as anywhere.
  void check_trigger(std::optional<Trigger>& t, const std::string& file,
                     const std::vector<std::string>* scope = nullptr) {
    if (!t) return;
    for (auto& group : t->groups)
      for (Condition& c : group) {
        if (auto* s = std::get_if<StoryboardElementStateCondition>(&c.kind)) {
          const SourceLocation where{file, c.place.path, c.place.line};
          std::vector<std::pair<std::vector<std::string>, std::string>> elements;
          for (const DeclaredElement& d : declared_[s->type]) elements.emplace_back(d.path, d.key);
          ReferenceMatch match = resolve_reference(s->ref, elements);
          if (match.keys.size() > 1 && scope != nullptr) {
            ReferenceMatch own;
            for (const std::string& key : match.keys) {
              const std::vector<std::string>& path = declared(s->type, key).path;
              if (path.size() > scope->size() && std::equal(scope->begin(), scope->end(), path.begin()))
                own.keys.push_back(key);
            }
            if (own.keys.size() == 1) match = own;
          }
          if (match.keys.empty()) {
            std::vector<std::string> choices;
            for (const DeclaredElement& d : declared_[s->type]) choices.push_back(d.path.back());
            throw ScenarioError(where, fmt::format("no {} named \"{}\" in the storyboard{}", s->type, s->ref,
                                                   did_you_mean(split_path(s->ref).back(), choices)));
          }
          if (match.keys.size() > 1) {
            const DeclaredElement& a = declared(s->type, match.keys[0]);
            const DeclaredElement& b = declared(s->type, match.keys[1]);
            throw ScenarioError(
                where, fmt::format("\"{}\" names more than one {}: \"{}\" (line {}) and \"{}\" (line {}); name one by "
                                   "its path, e.g. storyboardElementRef=\"{}\"",
                                   s->ref, s->type, join_path(a.path), a.line, join_path(b.path), b.line,
                                   join_path(a.path)));
          }
          s->key = match.keys.front();
        }
        if (const auto* b = std::get_if<ByEntityCondition>(&c.kind)) {
          for (const std::string& name : b->triggering_entities) check_entity(name, c, file);
          std::visit(
              [&](const auto& kind) {
                using K = std::decay_t<decltype(kind)>;
                std::vector<std::string> names;
                if constexpr (std::is_same_v<K, TimeToCollisionCondition> || std::is_same_v<K, CollisionCondition>) {
                  if (kind.entity) names.push_back(*kind.entity);
                } else if constexpr (requires { kind.entity; }) {
                  names.push_back(kind.entity);
                }
                if constexpr (requires { kind.entities; })
                  names.insert(names.end(), kind.entities.begin(), kind.entities.end());
                if constexpr (std::is_same_v<K, TimeToCollisionCondition>) {
                  if (kind.position) position_entities(*kind.position, names);
                } else if constexpr (requires { kind.position; }) {
                  position_entities(kind.position, names);
                }
                for (const std::string& name : names) check_entity(name, c, file);
              },
              b->condition);
        }
      }
  }
  void check_entity(const std::string& name, const Condition& c, const std::string& file) const {
    if (scenario_.entity(name) == nullptr)
      throw ScenarioError(SourceLocation{file, c.place.path, c.place.line},
                          fmt::format("no entity named \"{}\"{}", name, did_you_mean(name, entity_names_)));
  }

  void check_action_references(const PrivateAction& action, const Place& place) const {
    for (const std::string& name : referenced_entities(action))
      if (scenario_.entity(name) == nullptr)
        throw ScenarioError(SourceLocation{scenario_.file, place.path, place.line},
                            fmt::format("no entity named \"{}\"{}", name, did_you_mean(name, entity_names_)));
  }

  // Init's actions in an order where an action that names another entity (a position
  // relative to it, a speed relative to it, ...) runs after that entity's TeleportActions:
  // the standard gives Init's actions no order (1.3, 8.4.2: all of them are executed at
  // start-up, at 0 s), and files place an entity relative to one placed further down. A
  // stable topological order, so a file that needs none keeps its own; two entities placed
  // relative to each other (a cycle) are an error naming them.
  void order_init(std::vector<InitAction>& init) const {
    const auto is_teleport = [](const InitAction& a) { return std::holds_alternative<TeleportAction>(a.action); };
    std::vector<std::vector<std::string>> waits(init.size());
    for (std::size_t i = 0; i < init.size(); ++i)
      for (const std::string& name : referenced_entities(init[i].action))
        if (name != init[i].entity) waits[i].push_back(name);
    std::vector<InitAction> ordered;
    std::vector<bool> done(init.size(), false);
    const auto placed = [&](const std::string& entity) {
      for (std::size_t j = 0; j < init.size(); ++j)
        if (!done[j] && init[j].entity == entity && is_teleport(init[j])) return false;
      return true;
    };
    while (ordered.size() < init.size()) {
      bool progressed = false;
      for (std::size_t i = 0; i < init.size(); ++i) {
        if (done[i] || !std::all_of(waits[i].begin(), waits[i].end(), placed)) continue;
        done[i] = true;
        ordered.push_back(init[i]);
        progressed = true;
        break;  // from the start again: the file's order wherever it can be kept
      }
      if (progressed) continue;
      std::set<std::string> cycle;
      const InitAction* first = nullptr;
      for (std::size_t i = 0; i < init.size(); ++i)
        if (!done[i] && is_teleport(init[i])) {
          cycle.insert(init[i].entity);
          if (!first) first = &init[i];
        }
      if (!first)
        for (std::size_t i = 0; i < init.size(); ++i)
          if (!done[i]) first = &init[i];
      std::string names;
      for (const std::string& n : cycle) names += (names.empty() ? "\"" : ", \"") + n + "\"";
      throw ScenarioError(SourceLocation{scenario_.file, first->place.path, first->place.line},
                          fmt::format("the Init positions of {} refer to each other in a cycle: none of them can be "
                                      "placed first",
                                      names));
    }
    init = std::move(ordered);
  }

  void check_state_references(Storyboard& board) {
    const std::string& file = scenario_.file;
    check_trigger(board.stop_trigger, file);
    for (Story& story : board.stories)
      for (Act& act : story.acts) {
        check_trigger(act.start_trigger, file);
        check_trigger(act.stop_trigger, file);
        for (ManeuverGroup& g : act.groups)
          for (Maneuver& m : g.maneuvers) {
            const std::vector<std::string>* scope = nullptr;
            if (catalog_maneuvers_.count(m.key) != 0) scope = &declared("maneuver", m.key).path;
            for (Event& ev : m.events) check_trigger(ev.start_trigger, file, scope);
          }
      }
  }

  struct DeclaredElement {
    std::vector<std::string> path;  // names from the Story down to the element
    std::string key;
    int line = 0;
  };
  const DeclaredElement& declared(const std::string& type, const std::string& key) {
    const auto& all = declared_[type];
    return *std::find_if(all.begin(), all.end(), [&](const DeclaredElement& d) { return d.key == key; });
  }

  const Scenario& scenario_;
  Context& context_;
  std::vector<std::string> entity_names_;
  std::vector<std::string> path_;                              // names of the elements being read
  std::string act_key_;        // the Act being read
  std::string selecting_act_;  // while reading a group that selects triggering entities: its Act's key
  std::set<std::pair<std::string, std::string>> keys_;         // (type, key) given out
  std::map<std::string, std::vector<DeclaredElement>> declared_;  // by type, in file order
  std::set<std::string> catalog_maneuvers_;                    // keys of Maneuvers read from a catalog
};

}  // namespace

Storyboard read_storyboard(Element& storyboard, const Scenario& scenario, Context& context) {
  return StoryboardReader(scenario, context).read(storyboard);
}

}  // namespace orch::openscenario::reading
