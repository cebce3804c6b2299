package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.verify.QueryException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.List;
import org.junit.jupiter.api.Test;

/** Goals and strategies on small models of our own, in virtual time (deterministic by seed). */
class SteeringTest {

    /**
     * A combination lock: the code is a a b a b b; every input is acknowledged within a unit, a wrong one starts the
     * code again; the last b opens it (output open instead of ack). The environment waits a unit after each answer.
     */
    static final String LOCK = """
            const int CODE[6] = {0, 0, 1, 0, 1, 1};
            chan i_a, i_b, o_ack, o_open;
            int[0,5] k;
            process Lock() {
                clock x;
                state Idle, GotA { x <= 1 }, GotB { x <= 1 }, Open;
                init Idle;
                trans Idle -> GotA { sync i_a?; assign x = 0; },
                      Idle -> GotB { sync i_b?; assign x = 0; },
                      Open -> GotA { sync i_a?; assign x = 0; },
                      Open -> GotB { sync i_b?; assign x = 0; },
                      GotA -> Idle { guard CODE[k] == 0; sync o_ack!; assign k = k + 1; },
                      GotA -> Idle { guard CODE[k] != 0; sync o_ack!; assign k = 0; },
                      GotB -> Idle { guard k < 5 && CODE[k] == 1; sync o_ack!; assign k = k + 1; },
                      GotB -> Idle { guard CODE[k] != 1; sync o_ack!; assign k = 0; },
                      GotB -> Open { guard k == 5; sync o_open!; assign k = 0; };
            }
            process Env() {
                clock e;
                state Ready, Waiting;
                init Ready;
                trans Ready -> Waiting { guard e >= 1; sync i_a!; },
                      Ready -> Waiting { guard e >= 1; sync i_b!; },
                      Waiting -> Ready { sync o_ack?; assign e = 0; },
                      Waiting -> Ready { sync o_open?; assign e = 0; };
            }
            system Lock, Env;
            """;

    /** The lock of {@link #LOCK}, answering half a unit after each input. */
    static final class Lock implements Adapter {
        private static final int[] CODE = {0, 0, 1, 0, 1, 1};
        private AdapterContext context;
        private int k;

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            int symbol = input.channel().equals("a") ? 0 : 1;
            String answer;
            if (CODE[k] != symbol) {
                k = 0;
                answer = "ack";
            } else if (k == 5) {
                k = 0;
                answer = "open";
            } else {
                k++;
                answer = "ack";
            }
            context.clock().schedule(context.timeUnitMicros() / 2, () -> context.report(Event.of(answer)));
        }
    }

    private static OnlineTester tester(String model, Adapter system, TestOptions options) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        return new OnlineTester(n, TestInterface.fromNames(n), system, options);
    }

    @Test
    void theGoalStrategyOpensTheLockAndSaysWhen() throws Exception {
        for (long seed = 1; seed <= 5; seed++) {
            OnlineTester t = tester(LOCK, new Lock(), TestOptions.defaults(seed).withTimeout(20))
                    .steer(Steering.of(Strategy.GOAL, List.of("E<> Lock.Open")));
            TestResult r = t.run();
            assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
            assertTrue(r.explanation().startsWith("every goal was reached: 'E<> Lock.Open'"), r.explanation());
            GoalStatus goal = t.steeringReport().goals().get(0);
            assertEquals(GoalStatus.State.REACHED, goal.state());
            // six inputs, each answered half a unit later, the next a unit after that: open at 9 units, the least
            assertEquals(6, r.inputs(), r.toString());
            assertEquals(9_000, goal.micros(), goal.toString());
        }
    }

    @Test
    void randomInputsRarelyOpenTheLockInTheSameBudget() throws Exception {
        int opened = 0;
        for (long seed = 1; seed <= 10; seed++) {
            OnlineTester t = tester(LOCK, new Lock(), TestOptions.defaults(seed).withTimeout(20)
                    .withDelayPolicy(DelayPolicy.EAGER, 0))
                    .steer(Steering.of(Strategy.RANDOM, List.of("E<> Lock.Open")));
            TestResult r = t.run();
            if (t.steeringReport().goals().get(0).state() == GoalStatus.State.REACHED) {
                opened++;
            } else {
                // the goal, not reached, leaves the run without its purpose: INCONCLUSIVE, never PASSED
                assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
                assertTrue(r.explanation().startsWith("the timeout of 20 time units"), r.explanation());
                assertTrue(r.explanation().endsWith(", but not every goal was reached, so the run did not serve its"
                        + " purpose: not reached: 'E<> Lock.Open'"), r.explanation());
            }
        }
        assertTrue(opened <= 3, "random eager inputs opened the lock in " + opened + " of 10 runs");
    }

    @Test
    void aGoalTheCheckerProvesUnreachableIsSaidBeforeTheRunAndEndsIt() throws Exception {
        OnlineTester t = tester(LOCK, new Lock(), TestOptions.defaults(1).withTimeout(100))
                .steer(Steering.of(Strategy.GOAL, List.of("E<> Lock.Open and k == 3", "E<> Lock.Open")));
        SteeringReport before = t.steeringReport();
        assertEquals(GoalStatus.State.UNREACHABLE, before.goals().get(0).state());
        assertEquals(-1, before.goals().get(0).micros());
        assertTrue(before.goals().get(0).reason().startsWith("the model checker finds no reachable state where it"
                + " holds"), before.goals().get(0).reason());
        assertEquals(GoalStatus.State.OPEN, before.goals().get(1).state());
        TestResult r = t.run();
        // the reachable one is reached, then the run ends: the other can never be
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("a goal can no longer be reached, so the run cannot serve its purpose:"
                + " 'E<> Lock.Open and k == 3': the model checker finds no reachable state"), r.explanation());
        assertTrue(r.explanation().endsWith("(reached: 'E<> Lock.Open')"), r.explanation());
        assertEquals(9_000, r.durationMicros(), r.toString());
    }

    @Test
    void aGoalIsAnExistsEventuallyQuery() throws Exception {
        OnlineTester t = tester(LOCK, new Lock(), TestOptions.defaults(1));
        QueryException e = assertThrows(QueryException.class,
                () -> t.steer(Steering.of(Strategy.GOAL, List.of("A[] k < 6"))));
        assertEquals("goal 'A[] k < 6' is not a reachability query: a goal is written E<> p", e.getMessage());
        QueryException name = assertThrows(QueryException.class,
                () -> t.steer(Steering.of(Strategy.GOAL, List.of("E<> Lock.Opne"))));
        assertTrue(name.getMessage().equals("query 'E<> Lock.Opne', column 10: process Lock has no location 'Opne' (did you mean"
                + " 'Open'?)"), name.getMessage());
    }

    @Test
    void theCoverageStrategySetsTheLocksTrapInTheBudget() throws Exception {
        // the opening edge carries a trap (cov24's convention: a bool whose name starts with t_)
        String trapped = LOCK.replace("int[0,5] k;", "int[0,5] k; bool t_open;")
                .replace("sync o_open!; assign k = 0;", "sync o_open!; assign k = 0, t_open = true;");
        assertTrue(trapped.contains("t_open = true"), trapped);
        for (long seed = 1; seed <= 3; seed++) {
            OnlineTester t = tester(trapped, new Lock(), TestOptions.defaults(seed).withTimeout(40))
                    .steer(Steering.of(Strategy.COVERAGE, List.of()));
            TestResult r = t.run();
            assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
            assertEquals(new io.dtron.engine.coverage.Coverage.Figure(1, 1), r.coverage().trapFigure(),
                    r.coverage().summary());
            // every edge on an input or output of both processes, the lock's wrong answers included
            assertEquals(t.steeringReport().edges(), t.steeringReport().edgesCovered(), t.steeringReport().toString());
        }
    }

    /** A fork: after go, the system turns left or right for good. */
    static final String FORK = """
            chan i_go, o_left, o_right;
            process Fork() {
                clock x;
                state Start, Deciding { x <= 2 }, Left, Right;
                init Start;
                trans Start -> Deciding { sync i_go?; assign x = 0; },
                      Deciding -> Left { sync o_left!; },
                      Deciding -> Right { sync o_right!; };
            }
            process Env() {
                state Ready, Waiting, Done;
                init Ready;
                trans Ready -> Waiting { sync i_go!; },
                      Waiting -> Done { sync o_left?; },
                      Waiting -> Done { sync o_right?; };
            }
            system Fork, Env;
            """;

    /** Answers every input with output {@code answer} one unit later. */
    static final class Answer implements Adapter {
        private final String answer;
        private AdapterContext context;

        Answer(String answer) {
            this.answer = answer;
        }

        @Override
        public void start(AdapterContext c) {
            context = c;
        }

        @Override
        public void perform(Event input) {
            context.clock().schedule(context.timeUnitMicros(), () -> context.report(Event.of(answer)));
        }
    }

    @Test
    void aGoalTheSystemTurnsAwayFromEndsTheRunWithThatReason() throws Exception {
        OnlineTester t = tester(FORK, new Answer("left"), TestOptions.defaults(1).withTimeout(1000))
                .steer(Steering.of(Strategy.GOAL, List.of("E<> Fork.Right")));
        TestResult r = t.run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertEquals("a goal can no longer be reached, so the run cannot serve its purpose: 'E<> Fork.Right': after"
                + " output left() at t=1.000 was taken as Fork: Deciding -> Left, the implementation is in Fork.Left,"
                + " and no path of the model leads from there to the goal", r.explanation());
        assertEquals(1_000, r.durationMicros(), "ends when it happens, not at the timeout");
        GoalStatus goal = t.steeringReport().goals().get(0);
        assertEquals(GoalStatus.State.UNREACHABLE, goal.state());
        assertEquals(1_000, goal.micros());
    }

    /**
     * A job: a unit after go the system moves silently to Done, an urgent location, and leaves it at once with done.
     * No state the tester keeps after an event is in Done; the system was there when done came.
     */
    static final String JOB = """
            chan i_go, o_done;
            process Job() {
                clock x;
                state Idle, Work { x <= 1 }, Done;
                urgent Done;
                init Idle;
                trans Idle -> Work { sync i_go?; assign x = 0; },
                      Work -> Done { guard x >= 1; },
                      Done -> Idle { sync o_done!; };
            }
            process Env() { clock e; state Ready, Waiting; init Ready;
                trans Ready -> Waiting { guard e >= 1; sync i_go!; }, Waiting -> Ready { sync o_done?; assign e = 0; }; }
            system Job, Env;
            """;

    @Test
    void aGoalOnALocationEnteredAndLeftBetweenTwoEventsIsReachedWhenTheSecondShowsTheSystemWasThere()
            throws Exception {
        OnlineTester t = tester(JOB, new Answer("done"), TestOptions.defaults(1).withTimeout(100))
                .steer(Steering.of(Strategy.GOAL, List.of("E<> Job.Done")));
        TestResult r = t.run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals("every goal was reached: 'E<> Job.Done'", r.explanation());
        GoalStatus goal = t.steeringReport().goals().get(0);
        assertEquals(GoalStatus.State.REACHED, goal.state());
        // done is the first output, a unit after the first input: the run ends then, not at its timeout
        assertEquals(1, r.inputs(), r.toString());
        assertEquals(1, r.outputs(), r.toString());
        assertEquals(r.durationMicros(), goal.micros(), goal.toString());
    }

    /** A coin the system flips on every go: heads or tails; the environment asks again a unit after each. */
    static final String COIN = """
            chan i_go, o_heads, o_tails;
            process Coin() {
                clock x;
                state Idle, Flipping { x <= 1 }, Tails;
                init Idle;
                trans Idle -> Flipping { sync i_go?; assign x = 0; },
                      Tails -> Flipping { sync i_go?; assign x = 0; },
                      Flipping -> Idle { sync o_heads!; },
                      Flipping -> Tails { sync o_tails!; };
            }
            process Env() {
                clock e;
                state Ready, Waiting;
                init Ready;
                trans Ready -> Waiting { guard e >= 1; sync i_go!; },
                      Waiting -> Ready { sync o_heads?; assign e = 0; },
                      Waiting -> Ready { sync o_tails?; assign e = 0; };
            }
            system Coin, Env;
            """;

    @Test
    void aStarvedChoiceThatTheGoalNeedsEndsTheRunInconclusiveNamingIt() throws Exception {
        OnlineTester t = tester(COIN, new Answer("heads"), TestOptions.defaults(1).withTimeout(1000))
                .steer(new Steering(Strategy.GOAL, List.of("E<> Coin.Tails"), Steering.DEFAULT_HORIZON, 3, true));
        TestResult r = t.run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertEquals("the system's choice in Coin.Flipping, Env.Waiting is not 3-fair: o_heads (Coin: Flipping ->"
                + " Idle, Env: Waiting -> Ready) 4 times, o_tails (Coin: Flipping -> Tails, Env: Waiting -> Ready) 0"
                + " times; o_tails (Coin: Flipping -> Tails, Env: Waiting -> Ready) is starved and goal 'E<> Coin.Tails'"
                + " needs it (--fairness 3)", r.explanation());
        assertEquals(4, r.outputs(), r.toString());
        // without the bound, the goal stays reachable and the run goes on to its timeout
        OnlineTester unbounded = tester(COIN, new Answer("heads"), TestOptions.defaults(1).withTimeout(100))
                .steer(Steering.of(Strategy.GOAL, List.of("E<> Coin.Tails")));
        TestResult timeout = unbounded.run();
        assertEquals(Verdict.INCONCLUSIVE, timeout.verdict(), timeout.explanation());
        assertTrue(timeout.explanation().endsWith("not reached: 'E<> Coin.Tails'"), timeout.explanation());
        // when a stop condition, not the goals, decides when the run has done enough, the goal is only followed
        OnlineTester conditioned = tester(COIN, new Answer("heads"), TestOptions.defaults(1).withTimeout(100))
                .steer(new Steering(Strategy.GOAL, List.of("E<> Coin.Tails"), Steering.DEFAULT_HORIZON, -1, false));
        TestResult passed = conditioned.run();
        assertEquals(Verdict.PASSED, passed.verdict(), passed.explanation());
        assertEquals(GoalStatus.State.OPEN, conditioned.steeringReport().goals().get(0).state());
        assertEquals(GoalStatus.State.OPEN, unbounded.steeringReport().goals().get(0).state());
        // a fair coin reaches the goal
        OnlineTester fair = tester(COIN, new Answer("tails"), TestOptions.defaults(1).withTimeout(1000))
                .steer(new Steering(Strategy.GOAL, List.of("E<> Coin.Tails"), Steering.DEFAULT_HORIZON, 3, true));
        assertEquals(Verdict.PASSED, fair.run().verdict());
    }
}
