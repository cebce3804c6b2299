/**
 * The public API of DTRON: connect to the bus, send channel synchronisations
 * and listen to them.
 *
 * <p>A model's channel {@code i_move} with the attached global
 * {@code i_move_amount} is the bus channel {@code move} with the variable
 * {@code amount}. An adapter for it:
 *
 * <pre>{@code
 * IDtronChannel move = IDtronChannel.of("move", "amount");
 * IDtronChannel done = IDtronChannel.of("done");
 * try (Dtron dtron = Dtron.connect(DtronOptions.builder().clusterName("robot").build())) {
 *     dtron.addDtronListener(new DtronListener(move) {
 *         public void messageReceived(IDtronChannelValued message) {
 *             robot.move(message.getVariables().get("amount"));
 *             getDtron().send(done.constructValued(Map.of()));
 *         }
 *     });
 *     ...
 * }
 * }</pre>
 *
 * <p>Every member of a bus receives every message, its own included, in one
 * total order that is the same at all members. Values are immutable.
 * {@link io.dtron.api.DtronMembershipListener Membership listeners} hear who
 * joins and leaves; a tester announces the start of a run on
 * {@link io.dtron.api.Dtron#RUN_START} and its end on
 * {@link io.dtron.api.Dtron#RUN_STOP}; a {@link io.dtron.api.DtronAdapter}
 * can run in the tester's JVM.
 *
 * <p>Messages carry event times and their senders' clock offsets to the
 * tester; a member acknowledges the tester's inputs on
 * {@link io.dtron.api.Dtron#ACK} when it has applied them, and its
 * {@link io.dtron.api.RunClock} counts the run's time on the tester's clock.
 */
package io.dtron.api;
