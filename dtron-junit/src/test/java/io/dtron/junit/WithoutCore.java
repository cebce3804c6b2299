package io.dtron.junit;

import static org.junit.platform.engine.discovery.DiscoverySelectors.selectClass;

import org.junit.platform.engine.TestExecutionResult;
import org.junit.platform.testkit.engine.EngineTestKit;

/**
 * Runs the test class named by its argument on the JUnit Platform and prints each failure's message: run in a JVM
 * whose classpath lacks dtron-core, to see what a suite without it is told.
 */
public final class WithoutCore {
    private WithoutCore() {
    }

    public static void main(String[] args) throws ClassNotFoundException {
        EngineTestKit.engine("junit-jupiter").selectors(selectClass(Class.forName(args[0]))).execute().allEvents()
                .failed().stream().forEach(e -> System.out.println("failure: " + e.getPayload(
                        TestExecutionResult.class).flatMap(TestExecutionResult::getThrowable).map(Throwable::getMessage)
                        .orElse("")));
    }
}
