#!/usr/bin/python3
"""A Python client of the snooker shot-planning service (snooker.v1.ShotPlanner).

Uses Debian's python3-grpcio and python3-protobuf and the stubs generated from
proto/ at build time (build/examples/python_stubs; see examples/CMakeLists.txt):

    /usr/bin/python3 examples/python/snooker_client.py --target 127.0.0.1:50051 \
        --stubs build/examples/python_stubs [--tls-ca CA.pem]

It checks the server's health, asks for the model it works with (GetModel),
simulates a shot on a table whose black vision placed a hair past the left cushion
(the server moves it back and says so), and shows what a bad request gets back.
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
    from snooker.v1 import model_pb2, service_pb2_grpc, simulate_pb2, table_pb2

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

    # 4. Bad input: INVALID_ARGUMENT naming the field and the value.
    try:
        stub.Simulate(simulate_pb2.SimulateRequest(table=table, shot=table_pb2.Shot(speed=-1)),
                      timeout=args.timeout)
        expect(False, "a negative speed is refused")
    except grpc.RpcError as e:
        print("bad request:", e.code().name, "-", e.details())
        expect(e.code() == grpc.StatusCode.INVALID_ARGUMENT and "shot.speed = -1" in e.details(),
               "a negative speed is INVALID_ARGUMENT naming shot.speed")

    channel.close()
    print("all as expected" if not failures else "%d unexpected answers" % len(failures))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
