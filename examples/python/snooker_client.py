#!/usr/bin/python3
"""A Python client of the snooker shot-planning service (snooker.v1.ShotPlanner).

Uses Debian's python3-grpcio and python3-protobuf and the stubs generated from
proto/ at build time (build/examples/python_stubs; see examples/CMakeLists.txt):

    /usr/bin/python3 examples/python/snooker_client.py --target 127.0.0.1:50051 \
        --stubs build/examples/python_stubs [--tls-ca CA.pem]

It checks the server's health, asks for the model it works with (GetModel),
simulates a shot on a table whose black vision placed a hair past the left cushion
(the server moves it back and says so), plans a shot on the same table (Plan, and
PlanStream: the best shot so far as the search improves, then the final answer),
and shows what bad requests get back.
Exits 0 when every answer is as expected, 1 otherwise.
"""
import argparse
import math
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--target", default="127.0.0.1:50051", help="HOST:PORT of snooker serve")
    ap.add_argument("--stubs", required=True, help="folder of the generated Python stubs")
    ap.add_argument("--tls-ca", help="use TLS, trusting server certificates of this CA (PEM)")
    ap.add_argument("--timeout", type=float, default=10.0, help="each call's deadline, s")
    args = ap.parse_args()
    sys.path.insert(0, args.stubs)

    import grpc
    import health_pb2
    import health_pb2_grpc
    from snooker.v1 import model_pb2, plan_pb2, service_pb2_grpc, simulate_pb2, table_pb2

    if args.tls_ca:
        with open(args.tls_ca, "rb") as f:
            channel = grpc.secure_channel(args.target, grpc.ssl_channel_credentials(f.read()))
    else:
        channel = grpc.insecure_channel(args.target)
    failures = []

    def expect(ok, what):
        print(("  ok    " if ok else "  FAIL  ") + what)
        if not ok:
            failures.append(what)

    # 1. Health (grpc.health.v1), for the service by name.
    health = health_pb2_grpc.HealthStub(channel)
    status = health.Check(health_pb2.HealthCheckRequest(service="snooker.v1.ShotPlanner"),
                          timeout=args.timeout).status
    print("health:", health_pb2.HealthCheckResponse.ServingStatus.Name(status))
    expect(status == health_pb2.HealthCheckResponse.SERVING, "the service is SERVING")

    stub = service_pb2_grpc.ShotPlannerStub(channel)

    # 2. The model: table size, ball, and what the server repairs.
    model = stub.GetModel(model_pb2.GetModelRequest(), timeout=args.timeout)
    t = model.table
    print("model: table %.3f x %.3f m, ball radius %.5f m, %d pockets, vision tolerance %g mm"
          % (t.width_m, t.length_m, model.ball.radius_m, len(t.pockets),
             model.service.vision_tolerance_mm))
    expect(len(t.pockets) == 6 and t.width_m > 1.7, "GetModel describes a full-size table")

    # 3. A shot: the cue ball up the table into red-1; the black a hair (0.2 mm) past
    #    where a ball touches the left cushion, as vision might report it.
    contact = t.cushion_contact_distance_m
    table = table_pb2.TableState(balls=[
        table_pb2.Ball(id="cue", kind=table_pb2.CUE, position={"x": 0.9, "y": 0.6}),
        table_pb2.Ball(id="red-1", kind=table_pb2.RED, position={"x": 0.9, "y": 1.6}),
        table_pb2.Ball(id="black", kind=table_pb2.BLACK, position={"x": contact - 0.0002, "y": 3.0}),
    ])
    shot = table_pb2.Shot(speed=2.0, heading_deg=90, topspin=2.0 / model.ball.radius_m)
    answer = stub.Simulate(simulate_pb2.SimulateRequest(table=table, shot=shot), timeout=args.timeout)
    print("simulate: %s after %.3f s, %d events" % (answer.status, answer.duration_s, len(answer.events)))
    for w in answer.warnings:
        print("  warning:", w.message)
    for b in answer.final_balls:
        where = ("pocketed in " + b.pocket) if b.pocketed else "(%.4f, %.4f) m" % (b.position.x, b.position.y)
        print("  %-6s %s" % (b.id, where))
    expect(answer.status == "at rest", "the balls came to rest")
    expect(len(answer.warnings) == 1 and answer.warnings[0].ball_id == "black"
           and abs(answer.warnings[0].moved_mm - 0.2) < 1e-6,
           "the black was moved 0.2 mm back onto the bed, with a warning")
    kinds = [simulate_pb2.EventKind.Name(e.kind) for e in answer.events]
    expect("BALL_BALL" in kinds, "the cue ball hit red-1")
    expect(all(math.isfinite(b.position.x) and math.isfinite(b.position.y) for b in answer.final_balls),
           "every final position is finite")

    # 4. Bad input: INVALID_ARGUMENT naming the field and the value. The call is named
    #    with a request id, which the server's log line and its answer carry.
    try:
        stub.Simulate(simulate_pb2.SimulateRequest(table=table, shot=table_pb2.Shot(speed=-1)),
                      timeout=args.timeout, metadata=(("x-request-id", "example-bad-shot"),))
        expect(False, "a negative speed is refused")
    except grpc.RpcError as e:
        request_id = dict(e.initial_metadata() or ()).get("x-request-id")
        print("bad request:", e.code().name, "-", e.details(), "(request id %s)" % request_id)
        expect(e.code() == grpc.StatusCode.INVALID_ARGUMENT and "shot.speed = -1" in e.details(),
               "a negative speed is INVALID_ARGUMENT naming shot.speed")
        expect(request_id == "example-bad-shot", "the answer carries the call's request id")

    # 5. A plan on the same table: the robot's limits, a fixed seed and a simulation
    #    cap (so the answer does not depend on the machine's speed).
    limits = plan_pb2.RobotLimits(min_speed=0.5, max_speed=4.0, max_topspin_fraction=0.8,
                                  max_sidespin_fraction=0.4)
    request = plan_pb2.PlanRequest(table=table, ball_on=plan_pb2.BALL_ON_RED, limits=limits,
                                   time_budget_ms=5000, max_simulations=400,
                                   monte_carlo_samples=16, seed=11)
    plan = stub.Plan(request, timeout=args.timeout)
    print("plan: %d shots, %d simulations, %.1f ms" % (len(plan.shots), plan.simulations, plan.elapsed_ms))
    for w in plan.warnings:
        print("  warning:", w.message)
    for k, s in enumerate(plan.shots):
        print("  #%d %s into %s: P(pot) %.3f, speed %.3f m/s, heading %.2f deg, topspin %.1f, "
              "sidespin %.1f rad/s" % (k + 1, s.object_ball, s.pocket, s.pot_probability, s.speed,
                                       s.heading_deg, s.topspin, s.sidespin))
    expect(len(plan.shots) > 0 and plan.final, "the plan has shots and is final")
    expect(all(s.object_ball == "red-1" for s in plan.shots), "every shot pots red-1, the only red")
    rolling = lambda s: s.speed / model.ball.radius_m
    expect(all(limits.min_speed <= s.speed <= limits.max_speed
               and abs(s.topspin) <= limits.max_topspin_fraction * rolling(s) * (1 + 1e-9)
               and abs(s.sidespin) <= limits.max_sidespin_fraction * rolling(s) * (1 + 1e-9)
               and 0 <= s.pot_probability <= 1 for s in plan.shots),
           "every shot is within the robot's limits, its probability in [0, 1]")
    expect(len(plan.warnings) == 1 and plan.warnings[0].ball_id == "black",
           "the plan reports the black's repair too")

    messages = list(stub.PlanStream(request, timeout=args.timeout))
    progress = [m for m in messages if not m.final]
    print("plan stream: %d progress messages, then the final answer" % len(progress))
    expect(len(messages) >= 2 and messages[-1].final and len(progress) == len(messages) - 1,
           "the stream sends progress, then one final message last")
    expect(all(len(m.shots) == 1 for m in progress), "each progress message holds one shot")
    expect([s.SerializeToString() for s in messages[-1].shots] == [s.SerializeToString() for s in plan.shots],
           "the stream's final answer is Plan's")

    try:
        stub.Plan(plan_pb2.PlanRequest(table=table, time_budget_ms=0), timeout=args.timeout)
        expect(False, "a budget of 0 is refused")
    except grpc.RpcError as e:
        print("bad plan:", e.code().name, "-", e.details())
        expect(e.code() == grpc.StatusCode.INVALID_ARGUMENT and "time_budget_ms = 0" in e.details(),
               "a budget of 0 is INVALID_ARGUMENT naming time_budget_ms")

    channel.close()
    print("all as expected" if not failures else "%d unexpected answers" % len(failures))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
