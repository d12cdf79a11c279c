#include "openscenario/standard_elements.hpp"

#include <algorithm>
#include <array>

namespace orch::openscenario {
namespace {

// The schema's element names (1.0 to 1.3).
constexpr std::array kStandardElements = std::to_array<std::string_view>({
    "AbsoluteSpeed", "AbsoluteTargetLane", "AbsoluteTargetLaneOffset", "AbsoluteTargetSpeed",
    "AccelerationCondition", "AcquirePositionAction", "Act", "Action", "ActivateControllerAction", "Actions",
    "Actors", "AddEntityAction", "AngleCondition", "AnimationAction", "AnimationFile", "AnimationState",
    "AnimationType", "AppearanceAction", "AssignControllerAction", "AssignRouteAction", "Axle", "Axles",
    "BoundingBox", "Brake", "BrakeInput", "BrakePercent", "BrakeForce", "ByEntityCondition", "ByObjectType",
    "ByType", "ByValueCondition", "Catalog", "CatalogDefinition", "CatalogLocations", "CatalogReference",
    "Center", "CentralSwarmObject", "Clothoid", "ClothoidSpline", "ClothoidSplineSegment", "CollisionCondition",
    "Color", "ColorCmyk", "ColorRgb", "ComponentAnimation", "Condition", "ConditionGroup", "ConnectTrailerAction",
    "ConstraintGroup", "Controller", "ControllerAction", "ControllerCatalog", "ControllerDistribution",
    "ControllerDistributionEntry", "ControlPoint", "CustomCommandAction", "DeleteEntityAction",
    "Deterministic", "DeterministicMultiParameterDistribution", "DeterministicSingleParameterDistribution",
    "Dimensions", "Directory", "DisconnectTrailerAction", "DistanceCondition", "DistributionDefinition",
    "DistributionRange", "DistributionSet", "DistributionSetElement", "DomeImage", "DynamicConstraints",
    "EndOfRoadCondition", "Entities", "EntityAction", "EntityCondition", "EntityDistribution",
    "EntityDistributionEntry", "EntityObject", "EntityRef", "EntitySelection", "Environment", "EnvironmentAction",
    "EnvironmentCatalog", "Event", "ExternalObjectReference", "File", "FileHeader", "Fog", "FollowTrajectoryAction",
    "FrontAxle", "GearAction", "GeoPosition", "GlobalAction", "Histogram", "HistogramBin", "InfrastructureAction",
    "Init", "InitActions", "Knot", "Lane", "LaneChangeAction", "LaneChangeActionDynamics", "LaneChangeTarget",
    "LaneOffsetAction", "LaneOffsetActionDynamics", "LaneOffsetTarget", "LanePosition", "LateralAction",
    "LateralDistanceAction", "License", "LightState", "LightStateAction", "LightType", "LogNormalDistribution",
    "LogicFile", "LongitudinalAction", "LongitudinalDistanceAction", "Maneuver", "ManeuverCatalog",
    "ManeuverGroup", "ManualGear", "MiscObject", "MiscObjectCatalog", "ModifyRule", "MonitorDeclaration",
    "MonitorDeclarations", "NormalDistribution", "Nurbs", "ObjectController", "OffroadCondition", "OpenSCENARIO",
    "Orientation", "OverrideBrakeAction", "OverrideClutchAction", "OverrideControllerValueAction",
    "OverrideGearAction", "OverrideParkingBrakeAction", "OverrideSteeringWheelAction", "OverrideThrottleAction",
    "ParameterAction", "ParameterAddValueRule", "ParameterAssignment", "ParameterAssignments",
    "ParameterCondition", "ParameterDeclaration", "ParameterDeclarations", "ParameterModifyAction",
    "ParameterMultiplyByValueRule", "ParameterSetAction", "ParameterValueDistribution",
    "ParameterValueDistributionDefinition", "ParameterValueSet", "Pedestrian", "PedestrianAnimation",
    "PedestrianCatalog", "PedestrianGesture", "Performance", "Phase", "PoissonDistribution", "Polygon", "Polyline",
    "Position", "PositionInLaneCoordinates", "PositionInRoadCoordinates", "PositionOfCurrentEntity", "Precipitation",
    "Private", "PrivateAction", "ProbabilityDistributionSet", "ProbabilityDistributionSetElement", "Properties",
    "Property", "RandomRouteAction", "Range", "ReachPositionCondition", "RearAxle", "RelativeClearanceCondition",
    "RelativeDistanceCondition", "RelativeLanePosition", "RelativeLaneRange", "RelativeObjectPosition",
    "RelativeRoadPosition", "RelativeSpeedCondition", "RelativeSpeedToMaster", "RelativeTargetLane",
    "RelativeTargetLaneOffset", "RelativeTargetSpeed", "RelativeWorldPosition", "RoadCondition", "RoadCursor",
    "RoadNetwork", "RoadPosition", "RoadRange", "Route", "RouteCatalog", "RoutePosition", "RouteRef",
    "RoutingAction", "ScenarioDefinition", "ScenarioObject", "SceneGraphFile", "SelectedEntities", "Sensors",
    "Shape", "SimulationTimeCondition", "SpeedAction", "SpeedActionDynamics", "SpeedActionTarget",
    "SpeedCondition", "SpeedProfileAction", "SpeedProfileEntry", "StandStillCondition", "SteadyState",
    "StochasticDistribution", "StochasticDistributionType", "Stochastic", "StopTrigger", "Story", "Storyboard",
    "StoryboardElementStateCondition", "Sun", "SynchronizeAction", "TargetDistanceSteadyState",
    "TargetTimeSteadyState", "TeleportAction", "TimeHeadwayCondition", "TimeOfDay", "TimeOfDayCondition",
    "TimeReference", "TimeToCollisionCondition", "TimeToCollisionConditionTarget", "Timing", "TrafficAction",
    "TrafficAreaAction", "TrafficDefinition", "TrafficSignalAction", "TrafficSignalCondition", "TrafficSignalController",
    "TrafficSignalControllerAction", "TrafficSignalControllerCondition", "TrafficSignalState",
    "TrafficSignalStateAction", "TrafficSinkAction", "TrafficSourceAction", "TrafficStopAction",
    "TrafficSwarmAction", "Trajectory", "TrajectoryCatalog", "TrajectoryFollowingMode", "TrajectoryPosition",
    "TrajectoryRef", "TransitionDynamics", "TraveledDistanceCondition", "Trigger", "TriggeringEntities",
    "UniformDistribution", "UsedArea", "UserDefinedAction", "UserDefinedAnimation", "UserDefinedComponent",
    "UserDefinedDistribution", "UserDefinedLight", "UserDefinedValueCondition", "ValueConstraint",
    "ValueConstraintGroup", "ValueSetDistribution", "VariableAddValueRule", "VariableCondition",
    "VariableDeclaration", "VariableDeclarations", "VariableModifyAction", "VariableModifyRule",
    "VariableMultiplyByValueRule", "VariableSetAction", "Vehicle", "VehicleCatalog", "VehicleCategoryDistribution",
    "VehicleCategoryDistributionEntry", "VehicleComponent", "VehicleLight", "VehicleRoleDistribution",
    "VehicleRoleDistributionEntry", "Vertex", "VisibilityAction", "Waypoint", "Weather", "Wind", "WorldPosition",
    // Element names (not type names) the list above missed, and 1.3's.
    "AddValue", "CentralObject", "DirectionOfTravelDistribution", "FinalSpeed", "FromLaneCoordinates",
    "FromRoadCoordinates", "InRoutePosition", "ModifyAction", "MultiplyByValue", "None", "PositionStart",
    "RelativeAngleCondition", "Rule", "SensorReference", "SensorReferenceSet", "SetAction", "SetMonitorAction",
    "StartTrigger", "TargetPosition", "TargetPositionMaster", "Trailer", "TrailerAction", "TrailerCoupler", "TrailerHitch",
    "TrailerRef", "VariableAction", "ScenarioObjectTemplate", "TrafficArea", "TrafficDistribution",
    "TrafficDistributionEntry", "TrafficSignalGroupState",
});

}  // namespace

bool is_standard_element(std::string_view name) {
  return std::find(kStandardElements.begin(), kStandardElements.end(), name) != kStandardElements.end();
}

}  // namespace orch::openscenario
